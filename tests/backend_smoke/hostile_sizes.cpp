// Hostile sizes, offsets and counts on the bare backends (no validation wrapper): each call is refused by the
// backend itself with an error that names the call and the object, returns a null handle / false / 0, reaches
// neither the driver nor the validation layer, and leaves the device working. Before, a buffer of 2^64-1
// bytes was rounded up to 0 and accepted by the Vulkan backend, and the writes that followed corrupted the
// heap.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <functional>

#include "hostile_sizes.h"

using namespace bricklight::rhi;

namespace {

constexpr uint64_t kMax64 = UINT64_MAX;

struct Harness {
    std::unique_ptr<smoke::HostileBackend> backend = smoke::makeHostileBackend();
    IDevice& d = backend->device();

    // Runs a call that must be refused: `refused` says whether its result is a refusal; the backend's error
    // must name every needle; nothing may reach the layer below.
    void expectRefused(const std::string& what, const std::function<bool()>& refused, std::vector<std::string> needles) {
        INFO(backend->name() << ": " << what);
        backend->takeErrors();
        CHECK(refused());
        const std::vector<std::string> errors = backend->takeErrors();
        for (const auto& e : errors) UNSCOPED_INFO("error: " << e);
        REQUIRE_FALSE(errors.empty());
        for (const auto& needle : needles) CHECK(errors.front().find(needle) != std::string::npos);
        const std::vector<std::string> driver = backend->takeDriverMessages();
        for (const auto& m : driver) UNSCOPED_INFO("driver: " << m);
        CHECK(driver.empty());
    }

    // The device still works: a small buffer round-trips.
    void expectWorking() {
        const uint32_t words[4] = {1, 2, 3, 0xDEADBEEF};
        BufferHandle b = d.createBuffer({sizeof(words), 0, BufferUsage::ShaderRead, "still-working"}, words);
        REQUIRE(b);
        uint32_t back[4] = {};
        REQUIRE(d.readBuffer(b, 0, sizeof(back), back));
        CHECK(std::memcmp(back, words, sizeof(words)) == 0);
        d.destroy(b);
        CHECK(backend->takeErrors().empty());
        CHECK(backend->takeDriverMessages().empty());
    }
};

TextureDesc texture(const char* name, uint32_t w, uint32_t h, uint32_t depth = 1,
                    TextureDimension dim = TextureDimension::Texture2D, uint32_t mips = 1, Format f = Format::RGBA8_UNORM) {
    TextureDesc t;
    t.dimension = dim;
    t.format = f;
    t.width = w, t.height = h, t.depthOrLayers = depth, t.mipLevels = mips;
    t.usage = TextureUsage::Sampled;
    t.debugName = name;
    return t;
}

}  // namespace

TEST_CASE("hostile buffer and texture sizes are refused by the bare backend", "[smoke][hostile]") {
    Harness h;
    IDevice& d = h.d;
    const Limits& l = d.capabilities().limits;
    auto buffer = [&](const char* name, uint64_t size, uint32_t usage) {
        return [&d, name, size, usage] { return !d.createBuffer({size, 0, usage, name}); };
    };
    h.expectRefused("size 0", buffer("empty", 0, BufferUsage::ShaderRead), {"createBuffer 'empty'", "size"});
    h.expectRefused("size 2^64-1", buffer("all-of-it", kMax64, BufferUsage::Vertex), {"createBuffer 'all-of-it'", "exceeds"});
    h.expectRefused("size 2^64-4", buffer("almost-all", kMax64 - 3, BufferUsage::ShaderRead), {"'almost-all'", "exceeds"});
    h.expectRefused("size 2^63", buffer("half", uint64_t(1) << 63, BufferUsage::ShaderWrite), {"'half'", "exceeds"});
    h.expectRefused("size 2^44 (16 TiB)", buffer("terabytes", uint64_t(1) << 44, BufferUsage::Index), {"'terabytes'", "exceeds"});
    h.expectWorking();

    auto create = [&d](TextureDesc t) { return [&d, t] { return !d.createTexture(t); }; };
    h.expectRefused("width 2^31", create(texture("wide", 1u << 31, 1)), {"createTexture 'wide'", "exceeds"});
    h.expectRefused("2^32-1 squared, 33 mips", create(texture("vast", UINT32_MAX, UINT32_MAX, 1, TextureDimension::Texture2D, 33)),
                    {"'vast'", "exceeds"});
    h.expectRefused("maxTextureSize2D + 1", create(texture("limit2d", l.maxTextureSize2D + 1, 4)), {"'limit2d'", "exceeds"});
    h.expectRefused("maxTextureArrayLayers + 1",
                    create(texture("layers", 4, 4, l.maxTextureArrayLayers + 1, TextureDimension::Texture2DArray)),
                    {"'layers'", "exceed"});
    h.expectRefused("maxTextureSize3D + 1", create(texture("limit3d", 4, 4, l.maxTextureSize3D + 1, TextureDimension::Texture3D)),
                    {"'limit3d'", "exceeds"});
    h.expectRefused("more mips than the size has", create(texture("mips", 4, 4, 1, TextureDimension::Texture2D, 4)),
                    {"'mips'", "mipLevels 4"});
    h.expectRefused("2^32-1 mips", create(texture("allmips", 16, 16, 1, TextureDimension::Texture2D, UINT32_MAX)),
                    {"'allmips'", "mipLevels 4294967295"});
    h.expectRefused("an array at every limit (terabytes)",
                    create(texture("everything", l.maxTextureSize2D, l.maxTextureSize2D, l.maxTextureArrayLayers,
                                   TextureDimension::Texture2DArray, 1, Format::RGBA32_FLOAT)),
                    {"'everything'", "exceeds"});
    h.expectRefused("a 3D texture at its limit (gigabytes)",
                    create(texture("cube-of-floats", l.maxTextureSize3D, l.maxTextureSize3D, l.maxTextureSize3D,
                                   TextureDimension::Texture3D, 1, Format::RGBA32_FLOAT)),
                    {"'cube-of-floats'", "exceeds"});
    h.expectRefused("dimension 9", create(texture("odd", 4, 4, 1, TextureDimension(9))), {"'odd'", "dimension"});
    h.expectWorking();
}

TEST_CASE("hostile offsets, ranges and counts are refused by the bare backend", "[smoke][hostile]") {
    Harness h;
    IDevice& d = h.d;
    const BufferHandle b = d.createBuffer({64, 0, BufferUsage::ShaderRead | BufferUsage::ShaderWrite, "small"});
    const BufferHandle args = d.createBuffer({64, 0, BufferUsage::IndirectArgs, "args"});
    TextureDesc td = texture("array", 4, 4, 2, TextureDimension::Texture2DArray, 3);
    const TextureHandle t = d.createTexture(td);
    td.debugName = "other";
    const TextureHandle other = d.createTexture(td);
    REQUIRE((b && args && t && other));
    REQUIRE(h.backend->takeErrors().empty());
    std::vector<uint8_t> bytes(4096);

    h.expectRefused("writeBuffer past 2^64", [&] { return !d.writeBuffer(b, kMax64 - 3, bytes.data(), 8); }, {"writeBuffer", "'small'"});
    h.expectRefused("writeBuffer past the end", [&] { return !d.writeBuffer(b, 60, bytes.data(), 8); }, {"writeBuffer", "'small'"});
    h.expectRefused("readBuffer of 2^64-1 bytes", [&] { return !d.readBuffer(b, 8, kMax64, bytes.data()); }, {"readBuffer", "'small'"});
    h.expectRefused("copyBuffer source past 2^64", [&] { return !d.copyBuffer(b, 0, args, kMax64 - 3, 8); }, {"copyBuffer"});
    h.expectRefused("copyBuffer destination past the end", [&] { return !d.copyBuffer(b, 60, args, 0, 8); }, {"copyBuffer"});
    h.expectRefused("clearBuffer of 2^64-8 bytes", [&] { return !d.clearBuffer(b, {8, kMax64 - 7}, 0); }, {"clearBuffer", "'small'"});
    h.expectRefused("requestReadback of 2^64-1 bytes", [&] { return d.requestReadback(b, 0, kMax64) == 0; },
                    {"requestReadback", "'small'"});
    h.expectRefused("writeTexture mip 40", [&] { return !d.writeTexture(t, {40, 0, 0}, bytes.data()); }, {"writeTexture", "'array'"});
    h.expectRefused("writeTexture layers 1 + 2^32-1", [&] { return !d.writeTexture(t, {0, 1, UINT32_MAX}, bytes.data()); },
                    {"writeTexture", "'array'"});
    h.expectRefused("readTexture mip 2^32-1", [&] { return !d.readTexture(t, {UINT32_MAX, 0, 0}, bytes.data()); },
                    {"readTexture", "'array'"});
    h.expectRefused("copyTexture layer 5", [&] { return !d.copyTexture(other, {0, 0, 0}, t, {0, 5, 1}); }, {"copyTexture"});
    h.expectRefused("clearTexture mips 1 + 2^32-1", [&] { return !d.clearTexture(t, 1, UINT32_MAX, ClearValue{}); },
                    {"clearTexture", "'array'"});
    h.expectWorking();

    const ShaderBlob* fill = findShader("rhi_tests/fill_buffer.comp");
    REQUIRE(fill);
    const ShaderHandle shader = d.createShader({fill, ""});
    REQUIRE(shader);
    const uint32_t params[4] = {16, 1, 0, 0};
    DispatchState ds;
    ds.shader = shader;
    ds.label = "hostile";
    ds.bindings.constants.push(ConstantsBinding{0, params, sizeof(params)});
    ds.bindings.storageBuffers.push(StorageBufferBinding{0, b, {}, Access::Write});
    REQUIRE(d.dispatch(ds, 1, 1, 1));
    h.expectRefused("2^32-1 groups", [&] { return !d.dispatch(ds, UINT32_MAX, 1, 1); }, {"dispatch 'hostile'"});
    h.expectRefused("indirect arguments past 2^64", [&] { return !d.dispatchIndirect(ds, args, kMax64 - 3); },
                    {"dispatchIndirect 'hostile'"});
    DispatchState range = ds;
    range.bindings.storageBuffers[0].range = {kMax64 - 15, 32};
    h.expectRefused("a buffer view past 2^64", [&] { return !d.dispatch(range, 1, 1, 1); }, {"dispatch 'hostile'"});

    const ShaderHandle vs = d.createShader({findShader("rhi_tests/draw_color.vert"), ""});
    const ShaderHandle fs = d.createShader({findShader("rhi_tests/draw_color.frag"), ""});
    TextureDesc rt = texture("target", 8, 8);
    rt.usage = TextureUsage::RenderTarget;
    const TextureHandle target = d.createTexture(rt);
    const float vertices[3][7] = {{-1, -1, 0, 1, 0, 0, 1}, {3, -1, 0, 0, 1, 0, 1}, {-1, 3, 0, 0, 0, 1, 1}};
    const BufferHandle vb = d.createBuffer({sizeof(vertices), 0, BufferUsage::Vertex, "vertices"}, vertices);
    const uint32_t indices[3] = {0, 1, 2};
    const BufferHandle ib = d.createBuffer({sizeof(indices), 0, BufferUsage::Index, "indices"}, indices);
    REQUIRE((vs && fs && target && vb && ib));
    DrawCallState s;
    s.vertexShader = vs;
    s.fragmentShader = fs;
    s.label = "hostile";
    s.vertexInputs.push(VertexInput{0, VertexFormat::Float3, 0, 0});
    s.vertexInputs.push(VertexInput{1, VertexFormat::Float4, 0, 12});
    s.vertexBuffers.push(VertexBufferBinding{vb, 0, sizeof(vertices[0]), false});
    s.indexBuffer = IndexBufferBinding{ib, 0, IndexFormat::U32};
    ColorTarget ct;
    ct.view = textureMip(target, 0);
    ct.load = LoadOp::Clear;
    s.colorTargets.push(ct);
    REQUIRE(d.draw(s, DrawArgs{3, 1, 0, 0}));
    REQUIRE(h.backend->takeErrors().empty());
    h.expectRefused("drawIndirect past 2^64", [&] { return !d.drawIndirect(s, args, kMax64 - 3, false); }, {"drawIndirect 'hostile'"});
    DrawCallState bad = s;
    bad.indexBuffer.offset = kMax64 - 3;
    h.expectRefused("an index buffer offset past 2^64", [&] { return !d.drawIndexed(bad, DrawIndexedArgs{3, 1, 0, 0, 0}); },
                    {"drawIndexed 'hostile'"});
    bad = s;
    bad.vertexBuffers[0].offset = kMax64 - 3;
    h.expectRefused("a vertex buffer offset past 2^64", [&] { return !d.draw(bad, DrawArgs{3, 1, 0, 0}); }, {"draw 'hostile'"});
    bad = s;
    bad.viewport = Viewport{NAN, 0, 8, 8, 0, 1};
    h.expectRefused("a NaN viewport", [&] { return !d.draw(bad, DrawArgs{3, 1, 0, 0}); }, {"draw 'hostile'", "viewport"});
    bad.viewport = Viewport{0, 0, INFINITY, 8, 0, 1};
    h.expectRefused("an infinite viewport", [&] { return !d.draw(bad, DrawArgs{3, 1, 0, 0}); }, {"draw 'hostile'", "viewport"});
    bad.viewport = Viewport{0, 0, 8, 8, -1, 2};
    h.expectRefused("depths outside [0, 1]", [&] { return !d.draw(bad, DrawArgs{3, 1, 0, 0}); }, {"draw 'hostile'", "viewport"});
    h.expectWorking();
    d.waitIdle();
}
