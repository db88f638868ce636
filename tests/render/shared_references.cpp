#include "shared_references.h"

#include <cmath>

#include "backend_test.h"
#include "foliage_test_support.h"
#include "render_test_support.h"

namespace bricklight::testing {

scenes::SceneGeometry glossyFloorCornell() {
    scenes::SceneGeometry scene = scenes::cornellBox();
    bool found = false;
    for (scenes::TriangleMesh& m : scene.meshes)
        if (m.name == "floor") {
            m.albedo = glm::vec3(0.9f);
            m.metalness = 1.0f;
            m.roughness = 0.3f;
            m.specular = true;
            found = true;
        }
    REQUIRE(found);
    return scene;
}

namespace {

ReferenceRecipe recipe(std::string name, scenes::SceneGeometry scene, uint32_t width, uint32_t height, uint32_t spp,
                       uint32_t maxBounces) {
    ReferenceRecipe r{std::move(name), std::move(scene), {}, spp};
    r.options.width = width;
    r.options.height = height;
    r.options.maxBounces = maxBounces;
    return r;
}
ReferenceRecipe recipe(std::string name, scenes::SceneGeometry scene, uint32_t size, uint32_t spp, uint32_t maxBounces) {
    return recipe(std::move(name), std::move(scene), size, size, spp, maxBounces);
}

Reference traceRecipe(TestDevice& td, const std::string& name) {
    const ReferenceRecipe r = referenceRecipe(name);
    return pathTraced(td, r.scene, r.options, r.spp);
}

}  // namespace

std::vector<ReferenceRecipe> referenceRecipes() {
    const uint32_t all = render::PathTracerOptions{}.maxBounces;
    return {
        recipe("cornell", scenes::cornellBox(), kSharedReferenceSize, kSharedReferenceSpp, all),
        recipe("cornell-one-bounce", scenes::cornellBox(), kSharedReferenceSize, kSharedReferenceSpp, 1),
        recipe("cornell-glossy-floor", glossyFloorCornell(), kSharedReferenceSize, kSharedReferenceSpp, all),
        recipe("foliage-sun-behind-camera", foliageScene(false), 64, 256, all),
        recipe("foliage-sun-behind-cards", foliageScene(true), 64, 256, all),
        recipe("cornell-mirror-0.05-one-bounce", scenes::cornellMirror(0.05f), 128, 512, 1),
        recipe("cornell-mirror-0.3-one-bounce", scenes::cornellMirror(0.3f), 128, 512, 1),
        recipe("cornell-glass", scenes::cornellGlass(), 128, 512, all),
        recipe("corridor", scenes::corridor(), kCorridorWidth, kCorridorHeight, 1024, all),
    };
}

ReferenceRecipe referenceRecipe(const std::string& name) {
    for (ReferenceRecipe& r : referenceRecipes())
        if (r.name == name) return r;
    FAIL("no path-traced reference recipe named '" << name << "'");
    return {};
}

Reference cornellReference(TestDevice& td) { return traceRecipe(td, "cornell"); }
Reference cornellOneBounceReference(TestDevice& td) { return traceRecipe(td, "cornell-one-bounce"); }
Reference glossyFloorReference(TestDevice& td) { return traceRecipe(td, "cornell-glossy-floor"); }
Reference foliageReference(TestDevice& td, bool sunBehindCards) {
    return traceRecipe(td, sunBehindCards ? "foliage-sun-behind-cards" : "foliage-sun-behind-camera");
}
Reference mirrorFloorReference(TestDevice& td, float roughness) {
    REQUIRE((roughness == 0.05f || roughness == 0.3f));
    return traceRecipe(td, roughness == 0.05f ? "cornell-mirror-0.05-one-bounce" : "cornell-mirror-0.3-one-bounce");
}
Reference cornellGlassReference(TestDevice& td) { return traceRecipe(td, "cornell-glass"); }
Reference corridorReference(TestDevice& td) { return traceRecipe(td, "corridor"); }

}  // namespace bricklight::testing
