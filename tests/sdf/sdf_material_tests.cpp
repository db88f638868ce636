// The field's surface materials (sdf::InstanceDesc::material): every brick that holds a surface carries the
// surface-area-weighted mean of the materials of the triangles in its voxel, as the CPU computes it from the
// same rule (pairs of a triangle with a material and a lattice point within one brixel interval of it, weighted
// 1 − distance / interval);
// instances without a material leave their bricks unknown; bad materials are refused.
#include <glm/gtc/packing.hpp>

#include "backend_test.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

namespace {

glm::vec3 decodeRgb9e5(uint32_t v) {
    const float scale = std::exp2(float(int(v >> 27) - 24));
    return glm::vec3(float(v & 511u), float((v >> 9) & 511u), float((v >> 18) & 511u)) * scale;
}

struct Expected {
    glm::dvec3 albedo{0.0}, emission{0.0};
    double pairs = 0.0;
};

// The CPU's material of the voxel at world voxel `voxel` of size `vs`: the mean over (triangle, lattice point)
// pairs within one interval, weighted 1 − distance / interval.
Expected expectedMaterial(const scenes::SceneGeometry& g, const std::vector<glm::dvec3>& tris, const std::vector<uint32_t>& meshOf,
                          glm::ivec3 voxel, double vs) {
    Expected e;
    const double interval = vs / 7.0;
    for (size_t t = 0; t < meshOf.size(); ++t) {
        const scenes::TriangleMesh& m = g.meshes[meshOf[t]];
        double pairs = 0.0;
        for (int z = 0; z < 8; ++z)
            for (int y = 0; y < 8; ++y)
                for (int x = 0; x < 8; ++x) {
                    const glm::dvec3 p = (glm::dvec3(voxel) + glm::dvec3(x, y, z) / 7.0) * vs;
                    pairs += std::max(0.0, 1.0 - pointTriangleDistance(p, tris[3 * t], tris[3 * t + 1], tris[3 * t + 2]) / interval);
                }
        e.albedo += glm::dvec3(m.albedo) * pairs;
        e.emission += glm::dvec3(m.emission) * pairs;
        e.pairs += pairs;
    }
    return e;
}

void surfaceMaterials(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    // The Cornell box: white, red and green walls, two white blocks, an emitting light.
    scenes::SceneGeometry g = scenes::cornellBox();
    sdf::SceneDesc desc;
    desc.cascadeCount = 2;
    desc.finestVoxelSize = 10.0f;  // the box is 560 units (millimetres) across: 56 voxels
    desc.atlasBricksPerAxis = 32;
    desc.errorCallback = [&td](rhi::Severity, const std::string& m) { td.messages->push_back(m); };
    LoadedScene loaded = loadIntoSdf(*td.device, g, desc);
    REQUIRE(loaded.scene);
    const glm::vec3 centre = 0.5f * (g.boundsMin + g.boundsMax);
    loaded.scene->update(centre);
    const sdf::FieldSnapshot f = loaded.scene->readField();
    REQUIRE(f.brickMaterials.size() == f.brickAabbs.size() * 2);

    std::vector<glm::dvec3> tris;
    std::vector<uint32_t> meshOf;
    for (const scenes::MeshInstance& i : g.instances) {
        const scenes::TriangleMesh& m = g.meshes[i.mesh];
        for (size_t k = 0; k < m.indices.size(); k += 3) {
            for (int v = 0; v < 3; ++v) {
                const uint32_t j = m.indices[k + v];
                tris.push_back(glm::dvec3(i.transform * glm::vec4(m.positions[3 * j], m.positions[3 * j + 1], m.positions[3 * j + 2], 1.0f)));
            }
            meshOf.push_back(i.mesh);
        }
    }
    const sdf::FieldSnapshot::Cascade& c0 = f.cascades[0];
    uint32_t surfaceBricks = 0, known = 0, albedoOff = 0, emissionOff = 0, emitting = 0, red = 0;
    double worstAlbedo = 0.0;
    for (int z = 0; z < 64; ++z)
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const uint32_t brick = f.voxelState(0, {x, y, z});
                if (brick >= sdf::FieldSnapshot::kUnbuilt - 15 || f.brickAabbs[brick] == 0xFFFFFFFFu) continue;
                ++surfaceBricks;
                const uint32_t a = f.brickMaterials[2 * brick], em = f.brickMaterials[2 * brick + 1];
                const glm::ivec3 voxel = c0.origin + glm::ivec3(x, y, z);
                const Expected e = expectedMaterial(g, tris, meshOf, voxel, c0.voxelSize);
                if ((a >> 24) != 255u || e.pairs == 0.0) continue;
                ++known;
                const glm::dvec3 albedo = glm::dvec3(glm::unpackUnorm4x8(a));
                const double off = glm::length(albedo - e.albedo / e.pairs);
                worstAlbedo = std::max(worstAlbedo, off);
                albedoOff += off > 0.03;
                const glm::dvec3 emission = glm::dvec3(decodeRgb9e5(em)), expectedEmission = e.emission / e.pairs;
                emissionOff += glm::length(emission - expectedEmission) > 0.03 * std::max(1.0, glm::length(expectedEmission));
                emitting += emission.x > 1.0f;
                red += albedo.r > 0.5 && albedo.g < 0.2;
            }
    INFO(surfaceBricks << " surface bricks, " << known << " with a material; albedo off by > 0.03 in " << albedoOff
                       << " (worst " << worstAlbedo << "), emission off in " << emissionOff << "; " << emitting << " emitting, " << red << " red");
    CHECK(surfaceBricks > 1000);
    CHECK(known == surfaceBricks);
    CHECK(albedoOff <= surfaceBricks / 100);
    CHECK(emissionOff <= surfaceBricks / 100);
    CHECK(emitting > 4);
    CHECK(red > 50);
    REQUIRE_NO_MESSAGES(td);

    // An instance without a material leaves its bricks unknown; bad materials are refused, changing nothing.
    Error error;
    auto bare = sdf::SdfScene::create(*td.device, desc, &error);
    REQUIRE(bare);
    std::vector<sdf::MeshHandle> meshes = createMeshes(*bare, g);
    for (const scenes::MeshInstance& i : g.instances) REQUIRE(bare->addInstance({meshes[i.mesh], i.transform}));
    bare->update(centre);
    const sdf::FieldSnapshot fb = bare->readField();
    uint32_t bareKnown = 0;
    for (size_t b = 0; b < fb.brickAabbs.size(); ++b) bareKnown += (fb.brickMaterials[2 * b] >> 24) != 0u;
    CHECK(bareKnown == 0);
    sdf::InstanceDesc bad{meshes[0], glm::mat4(1.0f)};
    bad.material = sdf::SurfaceMaterial{glm::vec3(1.5f, 0.5f, 0.5f), glm::vec3(0.0f)};
    CHECK_FALSE(bare->addInstance(bad));
    CHECK(bare->lastError().code == ErrorCode::InvalidArgument);
    CHECK(bare->lastError().message.find("albedo") != std::string::npos);
    bad.material = sdf::SurfaceMaterial{glm::vec3(0.5f), glm::vec3(std::nanf(""), 0.0f, 0.0f)};
    CHECK_FALSE(bare->addInstance(bad));
    CHECK(bare->lastError().message.find("emission") != std::string::npos);
    td.messages->clear();
}

}  // namespace

BACKEND_TEST("sdf bricks carry their instances' surface materials", "[sdf][quick]", surfaceMaterials)
