// The suite's cache of path-traced references (reference_cache.h): the key follows the content, and an image
// read from the cache is the image the path tracer makes.
#include "backend_test.h"
#include "reference_cache.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

void cacheFollowsContent(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const scenes::SceneGeometry cornell = scenes::cornellBox();
    render::PathTracerOptions o;
    o.width = o.height = 16;
    const std::string key = referenceKey(td, cornell, o, 4);
    REQUIRE(key.size() == 32);
    CHECK(referenceKey(td, cornell, o, 4) == key);  // the same content, the same key
    CHECK(referenceKey(td, cornell, o, 8) != key);  // more samples
    scenes::SceneGeometry brighter = cornell;
    brighter.meshes[0].albedo *= 0.5f;
    CHECK(referenceKey(td, brighter, o, 4) != key);  // one material
    render::PathTracerOptions seeded = o;
    seeded.seed = 2;
    CHECK(referenceKey(td, cornell, seeded, 4) != key);  // another sample sequence
    // Traced (or read, if an earlier run kept it) and read again: the cached image is the traced one, every AOV.
    const Reference first = pathTraced(td, cornell, o, 4);
    const Reference second = pathTraced(td, cornell, o, 4);
    CHECK(second.fromCache());
    auto pt = traced(td, cornell, 16, 4);
    for (uint32_t a = 0; a < uint32_t(render::Aov::Count); ++a) {
        INFO("aov " << render::aovName(render::Aov(a)));
        CHECK(second.read(render::Aov(a)).rgb == first.read(render::Aov(a)).rgb);
        CHECK(pt->read(render::Aov(a)).rgb == second.read(render::Aov(a)).rgb);
    }
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("path-traced references: the cache's key follows the content, and a cached image is the traced one", "[render][quick]",
             cacheFollowsContent)
