// Built-in scenes and the assimp loader.
#include "scene_geometry.h"

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/texture.h>
#include <dlfcn.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

namespace bricklight::scenes {

namespace {

void addQuad(TriangleMesh& m, const float (&q)[4][3]) {
    const uint32_t base = uint32_t(m.positions.size() / 3);
    for (const auto& v : q) m.positions.insert(m.positions.end(), {v[0], v[1], v[2]});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

TriangleMesh quadMesh(const char* name, std::initializer_list<std::array<std::array<float, 3>, 4>> quads, glm::vec3 albedo) {
    TriangleMesh m;
    m.name = name;
    m.albedo = albedo;
    for (const auto& q : quads) {
        float c[4][3];
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 3; ++k) c[i][k] = q[size_t(i)][size_t(k)];
        addQuad(m, c);
    }
    return m;
}

}  // namespace

uint64_t SceneGeometry::triangleCount() const {
    uint64_t n = 0;
    for (const MeshInstance& i : instances) n += meshes[i.mesh].triangleCount();
    return n;
}

void SceneGeometry::computeBounds() {
    boundsMin = glm::vec3(INFINITY);
    boundsMax = glm::vec3(-INFINITY);
    for (const MeshInstance& inst : instances) {
        const TriangleMesh& m = meshes[inst.mesh];
        for (size_t i = 0; i < m.positions.size(); i += 3) {
            glm::vec3 p = glm::vec3(inst.transform * glm::vec4(m.positions[i], m.positions[i + 1], m.positions[i + 2], 1.0f));
            boundsMin = glm::min(boundsMin, p);
            boundsMax = glm::max(boundsMax, p);
        }
    }
}

SceneGeometry cornellBox() {
    SceneGeometry s;
    s.name = "cornell";
    const glm::vec3 white(0.725f, 0.71f, 0.68f), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);
    s.meshes.push_back(quadMesh("floor", {{{{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}}}}, white));
    s.meshes.push_back(quadMesh("ceiling", {{{{556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}}}}, white));
    s.meshes.push_back(quadMesh("back wall", {{{{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}}}}, white));
    s.meshes.push_back(quadMesh("red wall", {{{{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}}}}, red));
    s.meshes.push_back(quadMesh("green wall", {{{{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}}}}, green));
    s.meshes.push_back(quadMesh("short block",
                                {{{{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}}},
                                 {{{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}}},
                                 {{{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}}},
                                 {{{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}}},
                                 {{{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}}}},
                                white));
    s.meshes.push_back(quadMesh("tall block",
                                {{{{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}}},
                                 {{{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}}},
                                 {{{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}}},
                                 {{{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}}},
                                 {{{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}}}},
                                white));
    TriangleMesh light = quadMesh("light", {{{{343, 548, 227}, {343, 548, 332}, {213, 548, 332}, {213, 548, 227}}}}, glm::vec3(0.78f));
    light.emission = glm::vec3(17, 12, 4);
    s.meshes.push_back(std::move(light));
    for (uint32_t i = 0; i < s.meshes.size(); ++i) s.instances.push_back({i, glm::mat4(1.0f)});
    s.computeBounds();
    // Cornell's camera: at (278, 273, -800) looking along +z, 39.3 degrees vertical field of view.
    s.camera = {glm::vec3(278, 273, -800), glm::vec3(278, 273, 0), glm::vec3(0, 1, 0), 39.3f};
    return s;
}

TriangleMesh icosphere(uint32_t subdivisions) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<uint32_t> f = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                               3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    for (uint32_t s = 0; s < subdivisions; ++s) {
        std::vector<uint32_t> next;
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mids;
        auto mid = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = mids.find(key);
            if (it != mids.end()) return it->second;
            v.push_back((v[a] + v[b]) * 0.5f);
            return mids[key] = uint32_t(v.size() - 1);
        };
        for (size_t i = 0; i < f.size(); i += 3) {
            uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
            uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        f = std::move(next);
    }
    TriangleMesh m;
    m.name = "icosphere";
    for (const glm::vec3& p : v) {
        glm::vec3 n = glm::normalize(p);
        m.positions.insert(m.positions.end(), {n.x, n.y, n.z});
    }
    m.indices = std::move(f);
    return m;
}

TriangleMesh torus(float majorRadius, float minorRadius, uint32_t triangles) {
    const uint32_t minor = std::max(8u, uint32_t(std::sqrt(float(triangles) / 8.0f)));
    const uint32_t major = std::max(8u, triangles / (2 * minor));
    TriangleMesh m;
    m.name = "torus";
    for (uint32_t i = 0; i < major; ++i)
        for (uint32_t j = 0; j < minor; ++j) {
            const float u = 2.0f * float(M_PI) * float(i) / float(major), v = 2.0f * float(M_PI) * float(j) / float(minor);
            const float r = majorRadius + minorRadius * std::cos(v);
            m.positions.insert(m.positions.end(), {r * std::cos(u), minorRadius * std::sin(v), r * std::sin(u)});
        }
    for (uint32_t i = 0; i < major; ++i)
        for (uint32_t j = 0; j < minor; ++j) {
            const uint32_t a = i * minor + j, b = ((i + 1) % major) * minor + j;
            const uint32_t c = ((i + 1) % major) * minor + (j + 1) % minor, d = i * minor + (j + 1) % minor;
            m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
        }
    return m;
}

SceneGeometry proceduralField(uint32_t targetTriangles) {
    SceneGeometry s;
    s.name = "field";
    // Ground: a 128 x 128-quad grid, 40 x 40 units.
    TriangleMesh ground;
    ground.name = "ground";
    const uint32_t g = 128;
    for (uint32_t z = 0; z <= g; ++z)
        for (uint32_t x = 0; x <= g; ++x) {
            const float fx = float(x) / g * 40.0f - 20.0f, fz = float(z) / g * 40.0f - 20.0f;
            ground.positions.insert(ground.positions.end(), {fx, 0.15f * std::sin(fx * 0.7f) * std::cos(fz * 0.5f), fz});
        }
    for (uint32_t z = 0; z < g; ++z)
        for (uint32_t x = 0; x < g; ++x) {
            const uint32_t a = z * (g + 1) + x;
            ground.indices.insert(ground.indices.end(), {a, a + 1, a + g + 2, a, a + g + 2, a + g + 1});
        }
    s.meshes.push_back(std::move(ground));
    s.meshes.push_back(icosphere(5));        // 20480 triangles
    s.meshes.push_back(torus(0.6f, 0.22f, 16384));
    s.instances.push_back({0, glm::mat4(1.0f)});
    const uint64_t perPair = s.meshes[1].triangleCount() + s.meshes[2].triangleCount();
    const uint32_t pairs = std::max<uint32_t>(1, uint32_t((std::max<uint64_t>(targetTriangles, perPair) - s.meshes[0].triangleCount()) / perPair));
    const uint32_t side = uint32_t(std::ceil(std::sqrt(float(pairs))));
    for (uint32_t k = 0; k < pairs; ++k) {
        const float x = (float(k % side) + 0.5f) / float(side) * 32.0f - 16.0f;
        const float z = (float(k / side) + 0.5f) / float(side) * 32.0f - 16.0f;
        const float scale = 0.6f + 0.4f * std::fabs(std::sin(float(k) * 1.7f));
        glm::mat4 sphere = glm::translate(glm::mat4(1.0f), {x, scale + 0.1f, z}) * glm::scale(glm::mat4(1.0f), glm::vec3(scale));
        glm::mat4 ring = glm::translate(glm::mat4(1.0f), {x + 1.2f, 0.8f, z + 0.9f}) *
                         glm::rotate(glm::mat4(1.0f), float(k) * 0.9f, glm::vec3(0.3f, 1.0f, 0.2f));
        s.instances.push_back({1, sphere});
        s.instances.push_back({2, ring});
    }
    s.computeBounds();
    return s;
}

namespace {

// assimp's C API, loaded when a file is first opened: programs that only use built-in scenes (the
// benchmark copied to a bare GPU machine) need no assimp at run time.
struct AssimpApi {
    decltype(&aiImportFile) importFile = nullptr;
    decltype(&aiReleaseImport) releaseImport = nullptr;
    decltype(&aiGetErrorString) errorString = nullptr;
    decltype(&aiGetMaterialColor) materialColor = nullptr;
    decltype(&aiGetMaterialTexture) materialTexture = nullptr;
    decltype(&aiGetMaterialFloatArray) materialFloats = nullptr;
    std::string loadError;
    AssimpApi() {
        void* lib = nullptr;
        for (const char* name : {"libassimp.so.5", "libassimp.so"})
            if ((lib = dlopen(name, RTLD_NOW | RTLD_LOCAL))) break;
        if (!lib) {
            loadError = "assimp (libassimp.so.5) is not installed: only the built-in scenes are available";
            return;
        }
        importFile = reinterpret_cast<decltype(importFile)>(dlsym(lib, "aiImportFile"));
        releaseImport = reinterpret_cast<decltype(releaseImport)>(dlsym(lib, "aiReleaseImport"));
        errorString = reinterpret_cast<decltype(errorString)>(dlsym(lib, "aiGetErrorString"));
        materialColor = reinterpret_cast<decltype(materialColor)>(dlsym(lib, "aiGetMaterialColor"));
        materialTexture = reinterpret_cast<decltype(materialTexture)>(dlsym(lib, "aiGetMaterialTexture"));
        materialFloats = reinterpret_cast<decltype(materialFloats)>(dlsym(lib, "aiGetMaterialFloatArray"));
        if (!importFile || !releaseImport || !errorString || !materialColor || !materialTexture || !materialFloats)
            loadError = "libassimp lacks its C API";
    }
};

const AssimpApi& assimp() {
    static AssimpApi api;
    return api;
}

}  // namespace

// The world transform of the node named `name` (lights hang off nodes by name), or false if none.
bool nodeTransform(const aiNode* node, const aiString& name, const aiMatrix4x4& parent, aiMatrix4x4* out) {
    if (!node) return false;
    const aiMatrix4x4 world = parent * node->mTransformation;
    if (node->mName == name) {
        *out = world;
        return true;
    }
    for (unsigned i = 0; i < node->mNumChildren; ++i)
        if (nodeTransform(node->mChildren[i], name, world, out)) return true;
    return false;
}

// Lights of the file: directional -> the sun (the first one), point and spot -> point lights (colour =
// radiant intensity, W/sr; directional: irradiance), area -> an emissive rectangle (colour = radiance)
// facing the light's direction. Ambient lights are skipped.
void importLights(const aiScene* scene, SceneGeometry& s) {
    bool sun = false;
    for (unsigned i = 0; i < scene->mNumLights; ++i) {
        const aiLight* l = scene->mLights[i];
        aiMatrix4x4 m;
        if (!nodeTransform(scene->mRootNode, l->mName, aiMatrix4x4(), &m)) m = aiMatrix4x4();
        const aiVector3D p = m * l->mPosition;
        aiMatrix3x3 r(m);
        aiVector3D d = r * l->mDirection;
        d.Normalize();
        const glm::vec3 colour(l->mColorDiffuse.r, l->mColorDiffuse.g, l->mColorDiffuse.b);
        if (l->mType == aiLightSource_DIRECTIONAL && !sun) {
            s.environment.sunDirection = -glm::vec3(d.x, d.y, d.z);
            s.environment.sunIrradiance = colour;
            sun = true;
        } else if (l->mType == aiLightSource_POINT || l->mType == aiLightSource_SPOT) {
            PointLight pl;
            pl.position = glm::vec3(p.x, p.y, p.z);
            pl.intensity = colour;
            pl.direction = glm::vec3(d.x, d.y, d.z);
            if (l->mType == aiLightSource_SPOT) {
                pl.innerConeRadians = l->mAngleInnerCone;
                pl.outerConeRadians = l->mAngleOuterCone;
            }
            s.pointLights.push_back(pl);
        } else if (l->mType == aiLightSource_AREA && l->mSize.x > 0.0f && l->mSize.y > 0.0f) {
            aiVector3D up = r * l->mUp;
            glm::vec3 n(d.x, d.y, d.z), u = glm::normalize(glm::vec3(up.x, up.y, up.z));
            if (!std::isfinite(u.x) || std::fabs(glm::dot(u, n)) > 0.999f) u = std::fabs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
            const glm::vec3 right = glm::normalize(glm::cross(u, n)) * (0.5f * l->mSize.x);
            const glm::vec3 upHalf = glm::normalize(glm::cross(n, right)) * (0.5f * l->mSize.y);
            const glm::vec3 c(p.x, p.y, p.z);
            TriangleMesh quad;
            quad.name = std::string("area light ") + l->mName.C_Str();
            quad.albedo = glm::vec3(0.0f);
            quad.emission = colour;
            for (const glm::vec3& q : {c - right - upHalf, c + right - upHalf, c + right + upHalf, c - right + upHalf})
                quad.positions.insert(quad.positions.end(), {q.x, q.y, q.z});
            // Counter-clockwise seen from the side the light faces (its direction): emits that way.
            const bool ccw = glm::dot(glm::cross(right, upHalf), n) > 0.0f;
            quad.indices = ccw ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
            s.instances.push_back({uint32_t(s.meshes.size()), glm::mat4(1.0f)});
            s.meshes.push_back(std::move(quad));
        }
    }
}

SceneGeometry loadModel(const std::string& path, std::string* error) {
    SceneGeometry s;
    s.name = path;
    const AssimpApi& api = assimp();
    if (!api.loadError.empty()) {
        if (error) *error = "cannot load '" + path + "': " + api.loadError;
        return s;
    }
    // No JoinIdenticalVertices: it merges NaN positions away silently; bad vertices must reach the check below.
    const aiScene* scene = api.importFile(path.c_str(), aiProcess_Triangulate | aiProcess_PreTransformVertices);
    if (!scene) {
        if (error) *error = "cannot load '" + path + "': " + api.errorString();
        return s;
    }
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
        const aiMesh* in = scene->mMeshes[i];
        TriangleMesh m;
        m.name = in->mName.length ? in->mName.C_Str() : "mesh " + std::to_string(i);
        for (unsigned v = 0; v < in->mNumVertices; ++v) {
            const aiVector3D& p = in->mVertices[v];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                if (error) *error = "'" + path + "': mesh '" + m.name + "' vertex " + std::to_string(v) + " is not finite";
                api.releaseImport(scene);
                return SceneGeometry{};
            }
            m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
        }
        for (unsigned f = 0; f < in->mNumFaces; ++f)  // points and lines are not surfaces: skipped
            if (in->mFaces[f].mNumIndices == 3)
                m.indices.insert(m.indices.end(), {in->mFaces[f].mIndices[0], in->mFaces[f].mIndices[1], in->mFaces[f].mIndices[2]});
        if (m.indices.empty()) continue;
        if (in->mNormals)
            for (unsigned v = 0; v < in->mNumVertices; ++v) {
                aiVector3D n = in->mNormals[v];
                const float length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
                if (!(length > 0.0f) || !std::isfinite(length)) n = aiVector3D(0.0f);  // falls back to the triangle's
                else n /= length;
                m.normals.insert(m.normals.end(), {n.x, n.y, n.z});
            }
        if (in->mTextureCoords[0])
            for (unsigned v = 0; v < in->mNumVertices; ++v) m.uvs.insert(m.uvs.end(), {in->mTextureCoords[0][v].x, 1.0f - in->mTextureCoords[0][v].y});
        if (scene->mMaterials && in->mMaterialIndex < scene->mNumMaterials) {
            const aiMaterial* mat = scene->mMaterials[in->mMaterialIndex];
            aiColor4D c;
            if (api.materialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == aiReturn_SUCCESS) m.albedo = {c.r, c.g, c.b};
            if (api.materialColor(mat, AI_MATKEY_COLOR_EMISSIVE, &c) == aiReturn_SUCCESS) m.emission = {c.r, c.g, c.b};
            // Metallic-roughness materials (glTF's factors where the file has them; defaults otherwise).
            m.specular = true;
            ai_real value = 0;
            unsigned one = 1;
            if (api.materialFloats(mat, AI_MATKEY_ROUGHNESS_FACTOR, &value, &one) == aiReturn_SUCCESS) m.roughness = std::clamp(float(value), 0.0f, 1.0f);
            one = 1;
            if (api.materialFloats(mat, AI_MATKEY_METALLIC_FACTOR, &value, &one) == aiReturn_SUCCESS) m.metalness = std::clamp(float(value), 0.0f, 1.0f);
            aiString texture;
            if ((api.materialTexture(mat, aiTextureType_BASE_COLOR, 0, &texture, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr) ==
                     aiReturn_SUCCESS ||
                 api.materialTexture(mat, aiTextureType_DIFFUSE, 0, &texture, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr) ==
                     aiReturn_SUCCESS) &&
                texture.length) {
                const std::string name = texture.C_Str();
                if (m.uvs.empty()) {
                    s.warnings.push_back("mesh '" + m.name + "': texture '" + name + "' but no texture coordinates; base colour factor used");
                } else if (name[0] == '*') {
                    // Embedded: "*N" is the N-th of the scene's textures; compressed ones (height 0) are kept
                    // as bytes for the renderer to decode.
                    const unsigned index = unsigned(std::atoi(name.c_str() + 1));
                    const aiTexture* t = index < scene->mNumTextures ? scene->mTextures[index] : nullptr;
                    if (t && t->mHeight == 0 && t->mWidth > 0) {
                        const auto* bytes = reinterpret_cast<const uint8_t*>(t->pcData);
                        m.embeddedTexture = std::make_shared<std::vector<uint8_t>>(bytes, bytes + t->mWidth);
                        // The format hint as an extension: the decoder picks its reader by it.
                        const std::string hint = t->achFormatHint[0] ? std::string(t->achFormatHint) : std::string("png");
                        m.baseColorTexture = path + name + "." + hint;
                    } else {
                        s.warnings.push_back("mesh '" + m.name + "': embedded texture " + name +
                                             " is missing or uncompressed (not supported); base colour factor used");
                    }
                } else {
                    const size_t slash = path.find_last_of('/');
                    m.baseColorTexture = name[0] == '/' || slash == std::string::npos ? name : path.substr(0, slash + 1) + name;
                }
            }
        }
        s.instances.push_back({uint32_t(s.meshes.size()), glm::mat4(1.0f)});
        s.meshes.push_back(std::move(m));
    }
    if (s.meshes.empty()) {
        api.releaseImport(scene);
        if (error) *error = "'" + path + "' holds no triangles";
        return s;
    }
    s.computeBounds();
    // A view from the front; the file's lights where it has any, else a sky and a sun.
    const glm::vec3 centre = (s.boundsMin + s.boundsMax) * 0.5f;
    const float size = glm::length(s.boundsMax - s.boundsMin);
    s.camera = {centre + glm::vec3(0.0f, 0.25f * size, 1.2f * size), centre, glm::vec3(0, 1, 0), 45.0f};
    importLights(scene, s);
    s.computeBounds();  // area lights became geometry
    if (scene->mNumLights == 0)
        s.environment = {glm::vec3(0.35f, 0.45f, 0.6f), glm::normalize(glm::vec3(0.4f, 1.0f, 0.3f)), glm::vec3(3.0f)};
    api.releaseImport(scene);
    return s;
}

const char* builtinSceneNames() { return "cornell, two-rooms[:THICKNESS], atrium, dynamic, field"; }

SceneGeometry loadScene(const std::string& nameOrPath, std::string* error) {
    if (nameOrPath == "cornell") return cornellBox();
    if (nameOrPath == "field") return proceduralField(1000000);
    if (nameOrPath == "atrium") return atrium();
    if (nameOrPath == "dynamic") return dynamicRoom();
    if (nameOrPath.rfind("two-rooms", 0) == 0) {
        float thickness = 0.1f;
        if (nameOrPath.size() > 9) {
            char* end = nullptr;
            const std::string value = nameOrPath.substr(nameOrPath[9] == ':' ? 10 : 9);
            thickness = std::strtof(value.c_str(), &end);
            if (nameOrPath[9] != ':' || value.empty() || *end || !(thickness > 0.0f && thickness <= 2.0f)) {
                if (error) *error = "'" + nameOrPath + "': the wall thickness must be a number in (0, 2], as in two-rooms:0.05";
                return {};
            }
        }
        return twoRooms(thickness);
    }
    return loadModel(nameOrPath, error);
}

}  // namespace bricklight::scenes
