#include "assimp_import.h"

#include <assimp/GltfMaterial.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/texture.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "assimp_api.h"
#include "guarded_io.h"
#include "model_checks.h"
#include "safe_file.h"

namespace bricklight::scenes {

namespace {

// The node count and depth of what assimp built, walked with a stack (the scene is assimp's own output,
// but formats without a check of their own reach here with whatever hierarchy the file described).
bool checkNodes(const aiScene* scene, const std::string& path, const LoadLimits& limits, std::string* error) {
    std::vector<std::pair<const aiNode*, uint32_t>> stack;
    if (scene->mRootNode) stack.push_back({scene->mRootNode, 1});
    uint64_t visited = 0;
    while (!stack.empty()) {
        const auto [node, depth] = stack.back();
        stack.pop_back();
        if (++visited > limits.maxNodes) {
            if (error) *error = "'" + path + "': more than " + std::to_string(limits.maxNodes) + " nodes " + raiseHint("maxNodes");
            return false;
        }
        if (depth > limits.maxNodeDepth) {
            if (error)
                *error = "'" + path + "': the node hierarchy is more than " + std::to_string(limits.maxNodeDepth) + " levels deep " +
                         raiseHint("maxNodeDepth");
            return false;
        }
        for (unsigned i = 0; i < node->mNumChildren; ++i)
            if (node->mChildren[i]) stack.push_back({node->mChildren[i], depth + 1});
    }
    return true;
}

bool checkCounts(const aiScene* scene, const std::string& path, const LoadLimits& limits, std::string* error) {
    uint64_t vertices = 0, indices = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
        const aiMesh* m = scene->mMeshes[i];
        vertices += m->mNumVertices;
        for (unsigned f = 0; f < m->mNumFaces; ++f) {
            if (m->mFaces[f].mNumIndices > limits.maxFaceIndices) {
                if (error)
                    *error = "'" + path + "': a face of " + std::to_string(m->mFaces[f].mNumIndices) + " corners, over the limit of " +
                             std::to_string(limits.maxFaceIndices) + " " + raiseHint("maxFaceIndices");
                return false;
            }
            indices += m->mFaces[f].mNumIndices;
        }
    }
    const char* field = vertices > limits.maxVertices ? "maxVertices" : indices > limits.maxIndices ? "maxIndices" : nullptr;
    if (!field) return true;
    if (error)
        *error = "'" + path + "': " + std::to_string(vertices) + " vertices and " + std::to_string(indices) +
                 " vertex indices, over the limits of " + std::to_string(limits.maxVertices) + " and " + std::to_string(limits.maxIndices) +
                 " " + raiseHint(field);
    return false;
}

// The world transform of the node named `name` (lights hang off nodes by name), or false if none.
bool nodeTransform(const aiNode* root, const aiString& name, aiMatrix4x4* out) {
    std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack;
    if (root) stack.push_back({root, root->mTransformation});
    while (!stack.empty()) {
        const auto [node, world] = stack.back();
        stack.pop_back();
        if (node->mName == name) {
            *out = world;
            return true;
        }
        for (unsigned i = 0; i < node->mNumChildren; ++i)
            if (node->mChildren[i]) stack.push_back({node->mChildren[i], world * node->mChildren[i]->mTransformation});
    }
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
        if (!nodeTransform(scene->mRootNode, l->mName, &m)) m = aiMatrix4x4();
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

// A texture file the material names, as a path the renderer opens: relative names are relative to the model's
// folder; Windows separators become '/' where no file has the name as written (spider.obj's MTL says
// ".\\SpiderTex.jpg"). False with `error` for a file outside the model's folder (unless allowed).
bool textureFile(const std::string& name, const std::string& path, const LoadLimits& limits, const std::string& what, const TriangleMesh& m,
                 std::string* file, std::string* error) {
    const size_t slash = path.find_last_of('/');
    *file = name[0] == '/' || slash == std::string::npos ? name : path.substr(0, slash + 1) + name;
    if (name.find('\\') != std::string::npos && ::access(file->c_str(), F_OK) != 0)
        std::replace(file->begin() + long(file->size() - name.size()), file->end(), '\\', '/');
    if (limits.allowOutsidePaths) return true;
    const std::string folder = canonicalFolderOf(path);
    if (isInsideFolder(*file, folder)) return true;
    if (error) *error = "mesh '" + m.name + "': its " + what + " " + outsideFolderMessage(*file, path, folder);
    return false;
}

// Alpha testing: glTF's alphaMode MASK with its alphaCutoff (default 0.5) and the base colour factor's alpha;
// BLEND, which a renderer without sorted transparency cannot draw, as MASK at 0.5 (with a warning); OBJ's map_d
// (an opacity map) as the coverage at 0.5. False with `error` for a cut-off that is not a number or an
// opacity map outside the model's folder.
bool importAlpha(const aiMaterial* mat, const std::string& path, const LoadLimits& limits, TriangleMesh& m, SceneGeometry& s,
                 std::string* error) {
    const AssimpApi& api = assimp();
    aiString mode;
    if (api.materialString(mat, AI_MATKEY_GLTF_ALPHAMODE, &mode) == aiReturn_SUCCESS) {
        const std::string name = mode.C_Str();
        if (name == "MASK" || name == "BLEND") {
            aiColor4D c;
            // The factor's alpha: glTF's baseColorFactor (assimp gives it as the diffuse colour too).
            if (api.materialColor(mat, AI_MATKEY_BASE_COLOR, &c) == aiReturn_SUCCESS ||
                api.materialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == aiReturn_SUCCESS) {
                if (!std::isfinite(c.a)) {
                    if (error) *error = "mesh '" + m.name + "': the base colour factor's alpha is not a finite number";
                    return false;
                }
                if (c.a < 0.0f || c.a > 1.0f)
                    s.warnings.push_back("mesh '" + m.name + "': the base colour factor's alpha " + std::to_string(c.a) +
                                         " is outside [0, 1]; clamped");
                m.baseAlpha = std::clamp(float(c.a), 0.0f, 1.0f);
            }
            m.alphaCutoff = 0.5f;
            if (name == "BLEND") {
                s.warnings.push_back("mesh '" + m.name + "': alphaMode BLEND is drawn as MASK with a cut-off of 0.5 (no blending)");
                return true;
            }
            ai_real cutoff = 0;
            unsigned one = 1;
            if (api.materialFloats(mat, AI_MATKEY_GLTF_ALPHACUTOFF, &cutoff, &one) == aiReturn_SUCCESS) {
                if (!std::isfinite(cutoff)) {
                    if (error) *error = "mesh '" + m.name + "': alphaCutoff is not a finite number";
                    return false;
                }
                if (cutoff < 0.0f || cutoff > 1.0f)
                    s.warnings.push_back("mesh '" + m.name + "': alphaCutoff " + std::to_string(cutoff) + " is outside [0, 1]; clamped");
                m.alphaCutoff = std::clamp(float(cutoff), 0.0f, 1.0f);
            }
        }
        return true;
    }
    aiString opacity;
    if (api.materialTexture(mat, aiTextureType_OPACITY, 0, &opacity, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr) != aiReturn_SUCCESS ||
        !opacity.length)
        return true;
    const std::string name = opacity.C_Str();
    if (m.uvs.empty()) {
        s.warnings.push_back("mesh '" + m.name + "': opacity map '" + name + "' but no texture coordinates; drawn opaque");
        return true;
    }
    if (name[0] == '*') {
        s.warnings.push_back("mesh '" + m.name + "': embedded opacity map " + name + " is not supported; drawn opaque");
        return true;
    }
    if (!textureFile(name, path, limits, "opacity map", m, &m.alphaTexture, error)) return false;
    m.alphaCutoff = 0.5f;
    return true;
}

// The material's base colour factor and texture, roughness, metalness, emission and alpha test. False with
// `error` for a texture the scene may not use (outside the model's folder) or a bad alpha cut-off.
bool importMaterial(const aiScene* scene, const aiMaterial* mat, const std::string& path, const LoadLimits& limits, TriangleMesh& m,
                    SceneGeometry& s, std::vector<std::shared_ptr<std::vector<uint8_t>>>& embedded, std::string* error) {
    const AssimpApi& api = assimp();
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
    if (!importAlpha(mat, path, limits, m, s, error)) return false;
    aiString texture;
    if (!((api.materialTexture(mat, aiTextureType_BASE_COLOR, 0, &texture, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr) ==
               aiReturn_SUCCESS ||
           api.materialTexture(mat, aiTextureType_DIFFUSE, 0, &texture, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr) ==
               aiReturn_SUCCESS) &&
          texture.length))
        return true;
    const std::string name = texture.C_Str();
    if (m.uvs.empty()) {
        s.warnings.push_back("mesh '" + m.name + "': texture '" + name + "' but no texture coordinates; base colour factor used");
        return true;
    }
    if (name[0] == '*') {
        // Embedded: "*N" is the N-th of the scene's textures; compressed ones (height 0) are kept as bytes
        // for the renderer to decode (one copy however many meshes use them).
        char* end = nullptr;
        const unsigned long index = std::strtoul(name.c_str() + 1, &end, 10);
        const aiTexture* t = *end == '\0' && index < scene->mNumTextures ? scene->mTextures[index] : nullptr;
        if (t && t->mHeight == 0 && t->mWidth > 0 && t->mWidth <= limits.maxFileBytes) {
            if (embedded.size() < scene->mNumTextures) embedded.resize(scene->mNumTextures);
            if (!embedded[index]) {
                const auto* bytes = reinterpret_cast<const uint8_t*>(t->pcData);
                embedded[index] = std::make_shared<std::vector<uint8_t>>(bytes, bytes + t->mWidth);
            }
            m.embeddedTexture = embedded[index];
            // The format hint as an extension: the decoder picks its reader by it.
            const std::string hint = t->achFormatHint[0] ? std::string(t->achFormatHint, strnlen(t->achFormatHint, HINTMAXTEXTURELEN))
                                                         : std::string("png");
            m.baseColorTexture = path + name + "." + hint;
        } else {
            s.warnings.push_back("mesh '" + m.name + "': embedded texture " + name +
                                 " is missing or uncompressed (not supported); base colour factor used");
        }
        return true;
    }
    return textureFile(name, path, limits, "base colour texture", m, &m.baseColorTexture, error);
}

SceneGeometry convert(const aiScene* scene, const std::string& path, const LoadLimits& limits, std::string* error) {
    SceneGeometry s;
    s.name = path;
    auto fail = [&](const std::string& why) {
        if (error) *error = why;
        return SceneGeometry{};
    };
    std::vector<std::shared_ptr<std::vector<uint8_t>>> embedded;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
        const aiMesh* in = scene->mMeshes[i];
        TriangleMesh m;
        m.name = in->mName.length ? in->mName.C_Str() : "mesh " + std::to_string(i);
        for (unsigned v = 0; v < in->mNumVertices; ++v) {
            const aiVector3D& p = in->mVertices[v];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                return fail("'" + path + "': mesh '" + m.name + "' vertex " + std::to_string(v) + " is not finite");
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
        if (scene->mMaterials && in->mMaterialIndex < scene->mNumMaterials &&
            !importMaterial(scene, scene->mMaterials[in->mMaterialIndex], path, limits, m, s, embedded, error))
            return SceneGeometry{};
        s.instances.push_back({uint32_t(s.meshes.size()), glm::mat4(1.0f)});
        s.meshes.push_back(std::move(m));
    }
    if (s.meshes.empty()) return fail("'" + path + "' holds no triangles");
    s.computeBounds();
    // A view from the front; the file's lights where it has any, else — unless its own surfaces emit (an interior lit
    // by its lamps, which a sky and a sun would light from outside through every gap) — a sky and a sun.
    const glm::vec3 centre = (s.boundsMin + s.boundsMax) * 0.5f;
    const float size = glm::length(s.boundsMax - s.boundsMin);
    s.camera = {centre + glm::vec3(0.0f, 0.25f * size, 1.2f * size), centre, glm::vec3(0, 1, 0), 45.0f};
    importLights(scene, s);
    s.computeBounds();  // area lights became geometry
    bool emits = false;
    for (const TriangleMesh& m : s.meshes) emits |= m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f;
    if (scene->mNumLights == 0 && !emits)
        s.environment = {glm::vec3(0.35f, 0.45f, 0.6f), glm::normalize(glm::vec3(0.4f, 1.0f, 0.3f)), glm::vec3(3.0f)};
    return s;
}

}  // namespace

SceneGeometry importModelInProcess(const std::string& path, const LoadLimits& limits, std::string* error) {
    const AssimpApi& api = assimp();
    if (!api.loadError.empty()) {
        if (error) *error = "'" + path + "': " + api.loadError;
        return {};
    }
    if (!checkModelFile(path, limits, error)) return {};
    GuardedFileSystem files(path, limits);
    // ValidateDataStructure first: it turns indices past a mesh's vertices (a PLY face whose list runs
    // into the next one) into an error before Triangulate reads them. No JoinIdenticalVertices: it merges
    // NaN positions away silently; bad vertices must reach the check in convert().
    const aiScene* scene =
        api.importFileEx(path.c_str(), aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_PreTransformVertices, files.io());
    if (!files.refusal().empty()) {
        if (scene) api.releaseImport(scene);
        if (error) *error = files.refusal();
        return {};
    }
    if (!scene) {
        if (error) *error = "'" + path + "': " + api.errorString();
        return {};
    }
    SceneGeometry s;
    if (checkNodes(scene, path, limits, error) && checkCounts(scene, path, limits, error)) s = convert(scene, path, limits, error);
    api.releaseImport(scene);
    return s;
}

}  // namespace bricklight::scenes
