// Vulkan and GL build the same decoded field from the same scene (brick slots may differ): per voxel the
// same state and per brixel the same stored value. Stated tolerance: 1 step of 255 (different shader
// compilers may contract the float math differently); the test also reports how many brixels differ.
#include "backend_test.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

#if defined(BRICKLIGHT_HAS_VULKAN) && defined(BRICKLIGHT_HAS_GL)
TEST_CASE("sdf Vulkan and GL build the same field", "[sdf][cross]") {
    std::string error;
    scenes::SceneGeometry g = scenes::loadModel(testModelPath("OBJ/spider.obj"), &error);
    REQUIRE(!g.meshes.empty());
    scenes::SceneGeometry cornell = scenes::cornellBox();
    auto build = [&](const std::string& backend, const scenes::SceneGeometry& geometry) {
        TestDevice td = makeDevice(backend);
        REQUIRE(td.device);
        const glm::vec3 extent = geometry.boundsMax - geometry.boundsMin;
        sdf::SceneDesc desc;
        desc.cascadeCount = 2;
        desc.finestVoxelSize = std::max(extent.x, std::max(extent.y, extent.z)) / 36.0f;
        desc.atlasBricksPerAxis = 32;
        LoadedScene loaded = loadIntoSdf(*td.device, geometry, desc);
        REQUIRE(loaded.scene);
        loaded.scene->update((geometry.boundsMin + geometry.boundsMax) * 0.5f);
        sdf::FieldSnapshot field = loaded.scene->readField();
        REQUIRE_NO_MESSAGES(td);
        return field;
    };
    for (const scenes::SceneGeometry* geometry : {&g, &cornell}) {
        FieldDifference d = compareFields(build("vulkan", *geometry), build("gl", *geometry));
        INFO(geometry->name << ": " << d.voxelsCompared << " voxels, " << d.stateMismatches << " state mismatches ("
                            << d.firstMismatch << "), " << d.brixelsDiffering << " brixels differ, largest difference "
                            << d.maxBrixelDifference);
        WARN(geometry->name << ": Vulkan vs GL: " << d.stateMismatches << " state mismatches, " << d.brixelsDiffering
                            << " brixels differ (largest " << d.maxBrixelDifference << "/255)");
        CHECK(d.stateMismatches == 0);
        CHECK(d.maxBrixelDifference <= 1);
    }
}
#endif
