// Distances of the built field against exact CPU point-triangle distances, at lattice samples within
// two voxels of the surfaces of real models (OBJ, PLY, glTF through assimp) and the Cornell box.
#include <random>

#include "backend_test.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

namespace {

// Stored values are min(d, band) / band in 8 bits: half a step of rounding (0.008 brixel) plus float
// error of world-space coordinates. Stated tolerance: 0.02 brixel intervals.
constexpr double kToleranceBrixels = 0.02;

struct DistanceCase {
    const char* name;
    scenes::SceneGeometry geometry;
};

void checkDistances(const std::string& backend, const DistanceCase& test) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry& g = test.geometry;
    const sdf::SceneDesc desc = modelSceneDesc(g, 2, td);
    LoadedScene loaded = loadIntoSdf(*td.device, g, desc);
    if (!loaded.scene) REQUIRE_NO_MESSAGES(td);
    REQUIRE(loaded.scene);
    const glm::vec3 center = (g.boundsMin + g.boundsMax) * 0.5f;
    loaded.scene->update(center);
    sdf::FieldSnapshot field = loaded.scene->readField();
    REQUIRE_NO_MESSAGES(td);

    Reference ref(g, desc.finestVoxelSize);
    std::mt19937 rng(1234);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto& tris = ref.triangles();
    uint64_t samples = 0, nearSurface = 0, failures = 0;
    double worst = 0.0;
    std::string firstFailure;
    for (uint32_t cascade = 0; cascade < desc.cascadeCount; ++cascade) {
        const double vs = field.cascades[cascade].voxelSize;
        const double band = sdf::kDistanceBandBrixels / 7.0 * vs;
        const glm::ivec3 origin = field.cascades[cascade].origin;
        for (int i = 0; i < 3000; ++i) {
            // A point on a random triangle, moved up to two voxels in each axis, snapped to the lattice.
            const size_t t = size_t(unit(rng) * double(tris.size() / 3)) % (tris.size() / 3);
            double u = unit(rng), v = unit(rng);
            if (u + v > 1) u = 1 - u, v = 1 - v;
            glm::dvec3 p = tris[3 * t] + u * (tris[3 * t + 1] - tris[3 * t]) + v * (tris[3 * t + 2] - tris[3 * t]);
            p += glm::dvec3(unit(rng) * 4 - 2, unit(rng) * 4 - 2, unit(rng) * 4 - 2) * vs;
            const glm::dvec3 inVoxels = p / vs;
            const glm::ivec3 world = glm::ivec3(glm::floor(inVoxels));
            const glm::ivec3 logical = world - origin;
            if (glm::any(glm::lessThan(logical, glm::ivec3(0))) || glm::any(glm::greaterThan(logical, glm::ivec3(63)))) continue;
            const glm::ivec3 b = glm::clamp(glm::ivec3(glm::round((inVoxels - glm::dvec3(world)) * 7.0)), glm::ivec3(0), glm::ivec3(7));
            const glm::dvec3 lattice = (glm::dvec3(world) + glm::dvec3(b) / 7.0) * vs;
            const double expected = ref.distance(lattice, band);
            const double got = field.sampleDistance(cascade, logical, b);
            samples++;
            if (expected < band) nearSurface++;
            const double error = std::fabs(got - expected) / (vs / 7.0);
            worst = std::max(worst, error);
            if (got < 0.0 || error > kToleranceBrixels) {
                if (!failures++)
                    firstFailure = "cascade " + std::to_string(cascade) + " voxel " + std::to_string(logical.x) + "," +
                                   std::to_string(logical.y) + "," + std::to_string(logical.z) + " brixel " +
                                   std::to_string(b.x) + "," + std::to_string(b.y) + "," + std::to_string(b.z) +
                                   ": got " + std::to_string(got) + " expected " + std::to_string(expected);
            }
        }
    }
    INFO(test.name << " on " << backend << ": " << samples << " samples (" << nearSurface
                   << " inside the band), worst error " << worst << " brixel, first failure: " << firstFailure);
    CHECK(samples > 4000);
    CHECK(nearSurface > samples / 8);
    CHECK(failures == 0);
    WARN(test.name << " on " << backend << ": worst error " << worst << " brixel over " << samples << " samples");
}

void distancesAllScenes(const std::string& backend) {
    std::string error;
    std::vector<DistanceCase> cases;
    cases.push_back({"cornell", scenes::cornellBox()});
    cases.push_back({"spider.obj", scenes::loadModel(testModelPath("OBJ/spider.obj"), &error)});
    cases.push_back({"Wuson.ply", scenes::loadModel(testModelPath("PLY/Wuson.ply"), &error)});
    cases.push_back({"2CylinderEngine.glb", scenes::loadModel(testModelPath("glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"), &error)});
    INFO(error);
    for (const DistanceCase& c : cases) {
        REQUIRE(!c.geometry.meshes.empty());
        checkDistances(backend, c);
    }
}

}  // namespace

BACKEND_TEST("sdf distances match exact point-triangle distances", "[sdf][quick]", distancesAllScenes)
