// The depth pyramid (include/bricklight/gbuffer/depth_pyramid.h) against a CPU reduction of the read-back depth, exactly,
// on the renderer's G-buffer depth at odd and even sizes, and sizes that take several groups and dispatches; and bad input refused with nothing recorded. Both
// backends, every record through the validation wrapper, the Vulkan validation layer on.
#include <algorithm>
#include <cmath>

#include "backend_test.h"
#include "bricklight/gbuffer/depth_pyramid.h"
#include "raster_renderer.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

// The reference: mip n + 1 texel (x, y) takes the min and the max over mip n's texels 2x..2x+1 (plus 2x+2 on the
// last column above an odd width), likewise in y.
std::vector<std::vector<glm::vec2>> cpuPyramid(const std::vector<float>& depth, uint32_t w, uint32_t h) {
    std::vector<std::vector<glm::vec2>> mips;
    std::vector<glm::vec2> m0(depth.size());
    for (size_t i = 0; i < depth.size(); ++i) m0[i] = glm::vec2(depth[i]);
    mips.push_back(m0);
    uint32_t pw = w, ph = h;
    for (uint32_t m = 1; m < gbuffer::depthPyramidMipCount(w, h); ++m) {
        const uint32_t cw = std::max(1u, pw / 2), ch = std::max(1u, ph / 2);
        std::vector<glm::vec2> next(size_t(cw) * ch);
        const std::vector<glm::vec2>& prev = mips.back();
        for (uint32_t y = 0; y < ch; ++y)
            for (uint32_t x = 0; x < cw; ++x) {
                const uint32_t x1 = std::min(2 * x + 1 + ((x == cw - 1 && (pw & 1)) ? 1u : 0u), pw - 1);
                const uint32_t y1 = std::min(2 * y + 1 + ((y == ch - 1 && (ph & 1)) ? 1u : 0u), ph - 1);
                glm::vec2 mm(1e30f, -1e30f);
                for (uint32_t yy = 2 * y; yy <= y1; ++yy)
                    for (uint32_t xx = 2 * x; xx <= x1; ++xx) {
                        mm.x = std::min(mm.x, prev[size_t(yy) * pw + xx].x);
                        mm.y = std::max(mm.y, prev[size_t(yy) * pw + xx].y);
                    }
                next[size_t(y) * cw + x] = mm;
            }
        mips.push_back(next);
        pw = cw;
        ph = ch;
    }
    return mips;
}

void pyramidMatchesCpu(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry scene = scenes::atrium();  // sky, near and far surfaces: a wide spread of depths
    // 67 × 45 and 64 × 64: one group, then a dispatch for the last mip; 200 × 75: six groups by two, each row's and
    // column's last one taking the remainder, then two mips; 1100 × 3: 34 groups in a row, then five mips from mip 5.
    for (const glm::uvec2 size : {glm::uvec2(67, 45), glm::uvec2(64, 64), glm::uvec2(1, 5), glm::uvec2(200, 75), glm::uvec2(1100, 3)}) {
        render::RasterOptions ro;
        ro.width = size.x;
        ro.height = size.y;
        ro.lightSamples = 1;
        ro.depthPyramid = true;
        std::string error;
        auto r = render::RasterRenderer::create(*td.device, scene, ro, &error);
        INFO(error);
        REQUIRE(r);
        r->render();
        const gbuffer::DepthPyramid* p = r->depthPyramid();
        REQUIRE(p);
        REQUIRE(p->mipCount() == gbuffer::depthPyramidMipCount(size.x, size.y));
        std::vector<float> depth(size_t(size.x) * size.y);
        REQUIRE(td.device->readTexture(r->gbuffer().depth, {}, depth.data()));
        const auto expected = cpuPyramid(depth, size.x, size.y);
        size_t sky = 0;
        for (float d : depth) sky += d == 1.0f ? 1 : 0;
        for (uint32_t m = 0; m < p->mipCount(); ++m) {
            const uint32_t w = rhi::mipExtent(size.x, m), h = rhi::mipExtent(size.y, m);
            std::vector<glm::vec2> got(size_t(w) * h);
            rhi::TextureSubresource sub;
            sub.mip = m;
            REQUIRE(td.device->readTexture(p->texture(), sub, got.data()));
            size_t wrong = 0;
            for (size_t i = 0; i < got.size(); ++i) wrong += got[i] != expected[m][i] ? 1 : 0;
            INFO(size.x << "x" << size.y << " mip " << m << " (" << w << "x" << h << "): " << wrong << " texels differ from the CPU reduction");
            CHECK(wrong == 0);
        }
        // The coarsest texel holds the whole image's range.
        const glm::vec2 top = expected.back()[0];
        CHECK(top.x == *std::min_element(depth.begin(), depth.end()));
        CHECK(top.y == *std::max_element(depth.begin(), depth.end()));
        if (size.x > 8 && size.y > 8) CHECK(sky > 0);  // the test sees both sky (depth 1) and geometry
    }
    REQUIRE_NO_MESSAGES(td);
}

void badInputRefused(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    Error error;
    CHECK_FALSE(gbuffer::DepthPyramid::create(*td.device, {0, 16}, &error));
    CHECK(error.message.find("size 0x16 is outside") != std::string::npos);
    CHECK_FALSE(gbuffer::DepthPyramid::create(*td.device, {16, 100000}, &error));
    CHECK(error.message.find("is outside") != std::string::npos);
    auto p = gbuffer::DepthPyramid::create(*td.device, {16, 8}, &error);
    INFO(error.message);
    REQUIRE(p);
    CHECK(p->mipCount() == 5);
    // Every mip, and the 32 × 32 texture of six mips bound to the slots a dispatch leaves unused.
    CHECK(p->memoryUse().totalBytes == (16 * 8 + 8 * 4 + 4 * 2 + 2 * 1 + 1 * 1) * 8 + (32 * 32 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1) * 8);
    auto texture = [&](rhi::Format format, uint32_t w, uint32_t h, uint32_t usage, const char* name) {
        rhi::TextureDesc d;
        d.format = format;
        d.width = w;
        d.height = h;
        d.usage = usage;
        d.debugName = name;
        return td.device->createTexture(d);
    };
    using namespace rhi::TextureUsage;
    const rhi::TextureHandle wrongSize = texture(rhi::Format::D32_FLOAT, 17, 8, Sampled | DepthTarget, "big depth");
    const rhi::TextureHandle wrongFormat = texture(rhi::Format::RGBA8_UNORM, 16, 8, Sampled, "colour");
    const rhi::TextureHandle unsampled = texture(rhi::Format::D32_FLOAT, 16, 8, DepthTarget, "unsampled depth");
    const rhi::TextureHandle dead = texture(rhi::Format::D32_FLOAT, 16, 8, Sampled | DepthTarget, "dead depth");
    td.device->destroy(dead);
    struct Case {
        rhi::TextureHandle t;
        const char* expected;
    };
    for (const Case& c : {Case{wrongSize, "'big depth' is 17x8, the pyramid 16x8"}, Case{wrongFormat, "'colour' has format RGBA8_UNORM"},
                          Case{unsampled, "'unsampled depth' lacks Sampled usage"}, Case{dead, "null or destroyed"},
                          Case{rhi::TextureHandle{}, "null or destroyed"}}) {
        error = {};
        CHECK_FALSE(p->build(c.t, &error));
        INFO(error.message);
        CHECK(error.message.find(c.expected) != std::string::npos);
    }
    // Nothing was recorded: the pyramid still holds what it was cleared to.
    std::vector<glm::vec2> mip0(16 * 8, glm::vec2(-1.0f));
    rhi::ClearValue v{};
    v.f[0] = v.f[1] = 0.25f;
    REQUIRE(td.device->clearTexture(p->texture(), 0, 1, v));
    CHECK_FALSE(p->build(wrongSize, &error));
    REQUIRE(td.device->readTexture(p->texture(), {}, mip0.data()));
    CHECK(std::all_of(mip0.begin(), mip0.end(), [](glm::vec2 t) { return t == glm::vec2(0.25f); }));
    for (rhi::TextureHandle t : {wrongSize, wrongFormat, unsampled}) td.device->destroy(t);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("depth pyramid: min/max mips match a CPU reduction of the depth, odd sizes included", "[classify][quick]", pyramidMatchesCpu)
BACKEND_TEST("depth pyramid: bad input is refused and records nothing", "[classify]", badInputRefused)
