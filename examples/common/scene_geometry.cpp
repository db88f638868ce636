// Built-in scenes, and scene selection by name or file.
#include "scene_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <numbers>

namespace bricklight::scenes {

namespace {

TriangleMesh quadMesh(const char* name, std::initializer_list<std::array<std::array<float, 3>, 4>> quads, glm::vec3 albedo) {
    TriangleMesh m;
    m.name = name;
    m.albedo = albedo;
    auto corner = [](const std::array<float, 3>& v) { return glm::vec3(v[0], v[1], v[2]); };
    for (const auto& q : quads) addQuad(m, corner(q[0]), corner(q[1]), corner(q[2]), corner(q[3]));
    return m;
}

}  // namespace

void addQuad(TriangleMesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    const uint32_t base = uint32_t(m.positions.size() / 3);
    for (const glm::vec3& v : {a, b, c, d}) m.positions.insert(m.positions.end(), {v.x, v.y, v.z});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

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

void addBox(TriangleMesh& m, glm::vec3 lo, glm::vec3 hi) {
    const uint32_t b = uint32_t(m.positions.size() / 3);
    for (int i = 0; i < 8; ++i)
        m.positions.insert(m.positions.end(), {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    const uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& f : faces) m.indices.insert(m.indices.end(), {b + f[0], b + f[1], b + f[2], b + f[0], b + f[2], b + f[3]});
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
            const float u = 2.0f * std::numbers::pi_v<float> * float(i) / float(major), v = 2.0f * std::numbers::pi_v<float> * float(j) / float(minor);
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

const char* builtinSceneNames() { return "cornell, cornell-glass, cornell-mirror[:ROUGHNESS], two-rooms[:THICKNESS], atrium, dynamic, field, foliage, corridor"; }

SceneGeometry loadScene(const std::string& nameOrPath, std::string* error, const LoadLimits& limits) {
    if (nameOrPath == "cornell") return cornellBox();
    if (nameOrPath == "cornell-glass") return cornellGlass();
    if (nameOrPath == "field") return proceduralField(1000000);
    if (nameOrPath == "atrium") return atrium();
    if (nameOrPath == "dynamic") return dynamicRoom();
    if (nameOrPath == "foliage") return foliage();
    if (nameOrPath == "corridor") return corridor();
    if (nameOrPath.rfind("cornell-mirror", 0) == 0) {
        float roughness = 0.05f;
        if (nameOrPath.size() > 14) {
            char* end = nullptr;
            const std::string value = nameOrPath.substr(nameOrPath[14] == ':' ? 15 : 14);
            roughness = std::strtof(value.c_str(), &end);
            if (nameOrPath[14] != ':' || value.empty() || *end || !(roughness >= 0.0f && roughness <= 1.0f)) {
                if (error) *error = "'" + nameOrPath + "': the floor's roughness must be a number in [0, 1], as in cornell-mirror:0.3";
                return {};
            }
        }
        return cornellMirror(roughness);
    }
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
    return loadModel(nameOrPath, error, limits);
}

}  // namespace bricklight::scenes
