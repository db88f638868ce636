// The path tracer and the fast path are never silently wrong where a CPU driver's loop limit ends their work
// (issue 35): llvmpipe and lavapipe end every loop of a shader invocation once all its loops together have run
// 65,535 iterations, and a ray through a stack of thousands of coincident quads (every BVH node overlaps every
// other) needs more. Such samples and pixels are counted (PathTracer::samplesCutShort,
// RasterRenderer::invocationsCutShort); where none is, the image is the one of a single quad.
#include "backend_test.h"
#include "image_metrics.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

// A grey wall at z = -1 and `copies` coincident green quads at z = 0 in front of it, under a white sky.
// `cutOut`: the quads are alpha-tested and cut out everywhere (base alpha below the cut-off); quad c lies at
// z = c * spacing (coincident cut-out quads are passed together, spaced ones one by one).
scenes::SceneGeometry quadStack(uint32_t copies, bool cutOut = false, float spacing = 0.0f) {
    scenes::SceneGeometry s;
    scenes::TriangleMesh wall;
    wall.name = "wall";
    wall.positions = {-2, -2, -1, 2, -2, -1, 2, 2, -1, -2, 2, -1};
    wall.indices = {0, 1, 2, 0, 2, 3};
    wall.albedo = glm::vec3(0.8f);
    scenes::TriangleMesh stack;
    stack.name = "stack";
    stack.albedo = glm::vec3(0.2f, 0.7f, 0.2f);
    if (cutOut) {
        stack.alphaCutoff = 0.5f;
        stack.baseAlpha = 0.25f;
    }
    for (uint32_t c = 0; c < copies; ++c) {
        const uint32_t base = uint32_t(stack.positions.size() / 3);
        const float z = float(c) * spacing;
        stack.positions.insert(stack.positions.end(), {-1, -1, z, 1, -1, z, 1, 1, z, -1, 1, z});
        stack.indices.insert(stack.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    s.meshes = {wall, stack};
    s.instances = {{0, glm::mat4(1.0f)}, {1, glm::mat4(1.0f)}};
    s.environment.skyRadiance = glm::vec3(1.0f);
    s.camera = {glm::vec3(0, 0, 4), glm::vec3(0), glm::vec3(0, 1, 0), 45.0f};
    s.computeBounds();
    return s;
}

void loopLimitIsCounted(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    constexpr uint32_t kSize = 32, kSpp = 4;
    auto single = traced(td, quadStack(1), kSize, kSpp);
    CHECK(single->samplesCutShort() == 0);
    const render::Image expected = single->read(render::Aov::Combined);
    // 100 copies: far below the limit; 12,000: a camera ray alone visits about 24,000 triangles.
    for (uint32_t copies : {100u, 12000u}) {
        auto pt = traced(td, quadStack(copies), kSize, kSpp);
        const uint64_t cut = pt->samplesCutShort();
        const render::ImageMetrics m = render::compareImages(pt->read(render::Aov::Combined), expected);
        WARN(backend << ": " << copies << " coincident quads, " << td.device->capabilities().deviceName << ": " << cut << " of "
                     << kSize * kSize * kSpp << " samples cut short; relMSE against one quad " << m.relMse);
        if (copies == 100) CHECK(cut == 0);
        // The property that holds on every device: either the image is the single quad's, or the samples that made
        // it differ are counted. (Measured on lavapipe and llvmpipe alike: 12,000 copies cut 872 of the 4,096 samples short.)
        if (cut == 0) CHECK(m.relMse < 1e-4);
        else CHECK(cut <= uint64_t(kSize) * kSize * kSpp);
    }
    REQUIRE_NO_MESSAGES(td);
}

// The fast path's direct light: sky rays from the wall cross the cut-out stack. 3,000 spaced quads cost a ray two
// traversals (traceRay tests the rest of the way as it goes), within the limit: the image is exact. 12,000
// coincident ones make each traversal visit all 24,000 triangles: either the image is the wall's alone or the
// pixels that differ are counted (measured: 745 of 1,024 on lavapipe and llvmpipe).
void fastPathLoopLimitIsCounted(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    constexpr uint32_t kSize = 32;
    render::RasterOptions ro;
    ro.width = ro.height = kSize;
    ro.lightSamples = 2;
    auto rendered = [&](const scenes::SceneGeometry& scene) {
        std::string error;
        auto r = render::RasterRenderer::create(*td.device, scene, ro, &error);
        INFO(error);
        REQUIRE(r);
        r->render();
        td.device->endFrame();
        return r;
    };
    auto single = rendered(quadStack(1, true));
    CHECK(single->invocationsCutShort() == 0);
    const render::Image expected = single->read(render::Aov::Combined);
    for (const auto& [copies, spacing] : {std::pair{3000u, 1e-4f}, std::pair{12000u, 0.0f}}) {
        auto r = rendered(quadStack(copies, true, spacing));
        const uint64_t cut = r->invocationsCutShort();
        const render::ImageMetrics m = render::compareImages(r->read(render::Aov::Combined), expected);
        WARN(backend << ": " << copies << " cut-out quads " << spacing << " apart, " << td.device->capabilities().deviceName << ": "
                     << cut << " of " << kSize * kSize << " pixels cut short; relMSE against one quad " << m.relMse);
        if (spacing > 0.0f) CHECK(cut == 0);
        if (cut == 0) CHECK(m.relMse < 1e-4);
        else CHECK(cut <= uint64_t(kSize) * kSize);
    }
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("fast path: pixels a driver's loop limit cuts short are counted, never silently wrong", "[render]",
             fastPathLoopLimitIsCounted)
BACKEND_TEST("path tracer: samples a driver's loop limit cuts short are counted, never silently wrong", "[render]", loopLimitIsCounted)
