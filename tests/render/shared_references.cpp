#include "shared_references.h"

#include "backend_test.h"
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

Reference cornellReference(TestDevice& td) { return pathTraced(td, scenes::cornellBox(), kSharedReferenceSize, kSharedReferenceSpp); }

Reference cornellOneBounceReference(TestDevice& td) {
    return pathTraced(td, scenes::cornellBox(), kSharedReferenceSize, kSharedReferenceSpp, true, 1, /*maxBounces*/ 1);
}

Reference glossyFloorReference(TestDevice& td) { return pathTraced(td, glossyFloorCornell(), kSharedReferenceSize, kSharedReferenceSpp); }

namespace {

void traceSharedReferences(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    for (const Reference& r : {cornellReference(td), cornellOneBounceReference(td), glossyFloorReference(td)}) {
        REQUIRE(r.read(render::Aov::Combined).width == kSharedReferenceSize);
        CHECK(imageMean(r.read(render::Aov::Combined)) > 0.0);
    }
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("path-traced references the comparisons share", "[render]", traceSharedReferences)

}  // namespace bricklight::testing
