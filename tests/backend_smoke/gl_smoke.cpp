// Smoke test of the OpenGL 4.5 backend on a headless context (OSMesa/llvmpipe here; EGL where asked
// with BRICKLIGHT_GL_CONTEXT=egl): compute + read-back, image write then sampled read, a depth-tested
// draw read back at known pixels (memory row 0 = clip y -1), culling with the Vulkan winding rule,
// indirect dispatch with GPU-written args, barrier counting, timestamps, and error reporting.
#include <catch2/catch.hpp>

#include <array>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_validation.h"
#include "hostile_sizes.h"

using namespace bricklight;
using namespace bricklight::rhi;

namespace {

struct Context {
    std::vector<std::string> errors;
    std::unique_ptr<IDevice> device;
    std::string createError;
    Context() {
        device = gl::createHeadlessDevice(
            gl::HeadlessApi::Auto, [this](Severity s, const std::string& m) {
                if (s == Severity::Error) errors.push_back(m);
            },
            &createError);
    }
};

Context& ctx() {
    static Context c;
    return c;
}

IDevice& dev() {
    INFO("createHeadlessDevice: " << ctx().createError);
    REQUIRE(ctx().device);
    ctx().errors.clear();
    return *ctx().device;
}

std::vector<std::string>& errors() { return ctx().errors; }

ShaderHandle shader(const char* name) {
    const ShaderBlob* blob = findShader(name);
    REQUIRE(blob);
    ShaderHandle h = dev().createShader({blob, ""});
    REQUIRE(h);
    return h;
}

std::vector<uint32_t> readU32(BufferHandle b, size_t count) {
    std::vector<uint32_t> out(count);
    REQUIRE(dev().readBuffer(b, 0, count * 4, out.data()));
    return out;
}

struct FillParams {
    uint32_t count, scale, offset;
};

}  // namespace

// hostile_sizes.cpp runs on the bare backend; GL's own errors (debug output) are the layer below it.
std::unique_ptr<smoke::HostileBackend> smoke::makeHostileBackend() {
    struct Gl final : HostileBackend {
        const char* name() const override { return "gl"; }
        IDevice& device() override { return dev(); }
        std::vector<std::string> takeErrors() override { return take(false); }
        std::vector<std::string> takeDriverMessages() override { return take(true); }
        std::vector<std::string> take(bool driver) {
            std::vector<std::string> taken, kept;
            for (std::string& e : errors()) {
                const bool fromDriver = e.rfind("GL error (", 0) == 0;
                (fromDriver == driver ? taken : kept).push_back(e);
            }
            errors() = std::move(kept);
            return taken;
        }
    };
    return std::make_unique<Gl>();
}

TEST_CASE("gl: device reports GL capabilities", "[gl]") {
    const Capabilities& caps = dev().capabilities();
    CHECK(caps.backendName == "gl");
    CHECK(caps.deviceName.find("OpenGL") != std::string::npos);
    CHECK(caps.limits.maxComputeGroupCount[0] >= 65535);
    CHECK(caps.limits.maxComputeGroupInvocations >= 1024);
    CHECK(caps.limits.maxColorTargets == 8);
    CHECK(caps.supports(Format::R32_UINT, FormatSupport::Storage | FormatSupport::StorageAtomic));
    CHECK(caps.supports(Format::RGBA8_UNORM, FormatSupport::RenderTarget | FormatSupport::Blendable |
                                                 FormatSupport::Filterable | FormatSupport::Storage));
    CHECK(caps.supports(Format::D32_FLOAT, FormatSupport::DepthTarget));
    CHECK_FALSE(caps.supports(Format::RGBA8_SRGB, FormatSupport::Storage));
    CHECK_FALSE(caps.supports(Format::R11G11B10_FLOAT, FormatSupport::Storage));
    CHECK_FALSE(caps.supports(Format::RGBA32_FLOAT, FormatSupport::StorageAtomic));
    CHECK(gl::barrierCount(dev()).has_value());
    // A device that is not the backend's own (a wrapper around one, or here the null device) cannot tell.
    std::unique_ptr<IDevice> foreign = createNullDevice();
    CHECK_FALSE(gl::barrierCount(*foreign).has_value());
}

TEST_CASE("gl: compute fill, read back, read-after-read needs no barrier", "[gl]") {
    IDevice& d = dev();
    ShaderHandle fill = shader("rhi_tests/smoke_gl_fill.comp");
    ShaderHandle twice = shader("rhi_tests/smoke_gl_double.comp");
    BufferHandle a = d.createBuffer({1000 * 4, 0, BufferUsage::ShaderRead | BufferUsage::ShaderWrite, "a"});
    BufferHandle b = d.createBuffer({1000 * 4, 0, BufferUsage::ShaderRead | BufferUsage::ShaderWrite, "b"});
    REQUIRE((a && b));

    FillParams params{1000, 3, 5};
    DispatchState s;
    s.shader = fill;
    s.label = "fill";
    s.bindings.constants.push(constants(0, params));
    s.bindings.storageBuffers.push({0, a, {}, Access::Write});
    const uint64_t before = gl::barrierCount(d).value();
    REQUIRE(d.dispatch(s, 16, 1, 1));
    CHECK(gl::barrierCount(d).value() == before);  // nothing was pending

    // Reader 1 after the writer: one barrier (SHADER_STORAGE). Reader 2: none (read-after-read).
    DispatchState r;
    r.shader = twice;
    r.label = "double";
    r.bindings.readBuffers.push({0, a, {}});
    r.bindings.storageBuffers.push({0, b, {}, Access::Write});
    REQUIRE(d.dispatch(r, 16, 1, 1));
    CHECK(gl::barrierCount(d).value() == before + 1);
    BufferHandle c = d.createBuffer({1000 * 4, 0, BufferUsage::ShaderRead | BufferUsage::ShaderWrite, "c"});
    r.bindings.storageBuffers[0].buffer = c;
    REQUIRE(d.dispatch(r, 16, 1, 1));
    CHECK(gl::barrierCount(d).value() == before + 1);

    auto va = readU32(a, 1000);
    auto vc = readU32(c, 1000);
    CHECK(gl::barrierCount(d).value() == before + 2);  // BUFFER_UPDATE for the read-backs (c written since)
    for (uint32_t i = 0; i < 1000; ++i) {
        REQUIRE(va[i] == i * 3 + 5);
        REQUIRE(vc[i] == 2 * (i * 3 + 5));
    }
    // Sub-range reads and writes.
    uint32_t word = 0xDEADBEEF;
    REQUIRE(d.writeBuffer(a, 40, &word, 4));
    uint32_t back[3] = {};
    REQUIRE(d.readBuffer(a, 36, 12, back));
    CHECK(back[0] == 9 * 3 + 5);
    CHECK(back[1] == 0xDEADBEEF);
    CHECK(back[2] == 11 * 3 + 5);
    CHECK(errors().empty());
    for (BufferHandle h : {a, b, c}) d.destroy(h);
}

TEST_CASE("gl: order-independent writers skip the write-after-write barrier", "[gl]") {
    IDevice& d = dev();
    ShaderHandle count = shader("rhi_tests/smoke_gl_count.comp");
    uint32_t zero = 0;
    BufferHandle counter = d.createBuffer({4, 0, BufferUsage::ShaderWrite, "counter"}, &zero);
    DispatchState s;
    s.shader = count;
    s.bindings.storageBuffers.push({0, counter, {}, Access::Atomic});
    const uint64_t before = gl::barrierCount(d).value();
    REQUIRE(d.dispatch(s, 2, 1, 1));
    REQUIRE(d.dispatch(s, 2, 1, 1));
    CHECK(gl::barrierCount(d).value() == before + 1);  // write-after-write needs one
    s.flags = DispatchFlags::NoBarrierWithPreviousWriter;
    REQUIRE(d.dispatch(s, 2, 1, 1));
    CHECK(gl::barrierCount(d).value() == before + 1);
    CHECK(readU32(counter, 1)[0] == 3 * 128);
    CHECK(errors().empty());
    d.destroy(counter);
}

TEST_CASE("gl: storage image write, then sampled read in a later dispatch", "[gl]") {
    IDevice& d = dev();
    ShaderHandle write = shader("rhi_tests/smoke_gl_image_write.comp");
    ShaderHandle sample = shader("rhi_tests/smoke_gl_image_sample.comp");
    TextureDesc td;
    td.format = Format::R32_UINT;
    td.width = 20;
    td.height = 12;
    td.usage = TextureUsage::Storage | TextureUsage::Sampled;
    td.debugName = "image";
    TextureHandle image = d.createTexture(td);
    BufferHandle out = d.createBuffer({20 * 12 * 4, 0, BufferUsage::ShaderWrite, "sampled"});
    SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = Filter::Nearest;
    SamplerHandle nearest = d.createSampler(sd);
    REQUIRE((image && out && nearest));

    DispatchState w;
    w.shader = write;
    w.bindings.storageImages.push({0, wholeTexture(image), Access::Write});
    REQUIRE(d.dispatch(w, 3, 2, 1));
    const uint64_t before = gl::barrierCount(d).value();
    DispatchState r;
    r.shader = sample;
    r.bindings.textures.push({0, wholeTexture(image), nearest});
    r.bindings.storageBuffers.push({0, out, {}, Access::Write});
    REQUIRE(d.dispatch(r, 3, 2, 1));
    CHECK(gl::barrierCount(d).value() == before + 1);  // TEXTURE_FETCH
    auto values = readU32(out, 20 * 12);
    std::vector<uint32_t> texels(20 * 12);
    REQUIRE(d.readTexture(image, {}, texels.data()));
    for (uint32_t y = 0; y < 12; ++y)
        for (uint32_t x = 0; x < 20; ++x) {
            REQUIRE(values[y * 20 + x] == x + 1000 * y + 7);
            REQUIRE(texels[y * 20 + x] == x + 1000 * y + 7);
        }
    CHECK(errors().empty());
    d.destroy(image);
    d.destroy(out);
    d.destroy(nearest);
}

TEST_CASE("gl: texture upload layout, clears and copies round-trip", "[gl]") {
    IDevice& d = dev();
    // A 2-layer array with 2 mips: initialData = layer 0 (mip 0, mip 1), then layer 1.
    TextureDesc td;
    td.dimension = TextureDimension::Texture2DArray;
    td.format = Format::R32_UINT;
    td.width = 4;
    td.height = 2;
    td.depthOrLayers = 2;
    td.mipLevels = 2;
    td.debugName = "array";
    std::vector<uint32_t> init;
    for (uint32_t layer = 0; layer < 2; ++layer) {
        for (uint32_t i = 0; i < 8; ++i) init.push_back(layer * 100 + i);
        for (uint32_t i = 0; i < 2; ++i) init.push_back(layer * 100 + 50 + i);
    }
    TextureHandle t = d.createTexture(td, init.data());
    REQUIRE(t);
    uint32_t mip1[4] = {};
    REQUIRE(d.readTexture(t, {1, 0, 0}, mip1));  // both layers of mip 1
    CHECK(mip1[0] == 50);
    CHECK(mip1[1] == 51);
    CHECK(mip1[2] == 150);
    CHECK(mip1[3] == 151);
    uint32_t layer1[8] = {};
    REQUIRE(d.readTexture(t, {0, 1, 1}, layer1));
    CHECK(layer1[0] == 100);
    CHECK(layer1[7] == 107);

    ClearValue cv{};
    cv.u[0] = 42;
    REQUIRE(d.clearTexture(t, 1, 1, cv));
    REQUIRE(d.readTexture(t, {1, 0, 0}, mip1));
    CHECK((mip1[0] == 42 && mip1[3] == 42));

    TextureHandle u = d.createTexture(td);
    REQUIRE(d.copyTexture(u, {0, 1, 1}, t, {0, 0, 1}));
    REQUIRE(d.readTexture(u, {0, 1, 1}, layer1));
    CHECK(layer1[5] == 5);

    // sRGB clear encodes the linear value (Vulkan parity): 0.5 -> 188.
    TextureDesc sd;
    sd.format = Format::RGBA8_SRGB;
    sd.width = sd.height = 2;
    TextureHandle s = d.createTexture(sd);
    ClearValue half{};
    half.f[0] = half.f[1] = half.f[2] = 0.5f;
    half.f[3] = 1.0f;
    REQUIRE(d.clearTexture(s, 0, 0, half));
    uint8_t px[16] = {};
    REQUIRE(d.readTexture(s, {}, px));
    CHECK(int(px[0]) == 188);
    CHECK(int(px[3]) == 255);
    CHECK(errors().empty());
    for (TextureHandle h : {t, u, s}) d.destroy(h);
}

namespace {
struct Vertex {
    float x, y, z;
    uint8_t rgba[4];
};

// Draws `verts` into `color` (+ `depth`) with the given state tweaks.
bool drawTriangles(IDevice& d, const std::vector<Vertex>& verts, TextureHandle color, TextureHandle depth,
                   LoadOp load, const std::function<void(DrawCallState&)>& tweak) {
    static ShaderHandle vs = shader("rhi_tests/smoke_gl_triangle.vert");
    static ShaderHandle fs = shader("rhi_tests/smoke_gl_triangle.frag");
    BufferHandle vb = d.createBuffer({verts.size() * sizeof(Vertex), 0, BufferUsage::Vertex, "vertices"}, verts.data());
    DrawCallState s;
    s.vertexShader = vs;
    s.fragmentShader = fs;
    s.label = "triangles";
    s.vertexInputs.push({0, VertexFormat::Float3, 0, 0});
    s.vertexInputs.push({1, VertexFormat::UByte4Norm, 0, 12});
    s.vertexBuffers.push({vb, 0, sizeof(Vertex), false});
    ColorTarget ct;
    ct.view = wholeTexture(color);
    ct.load = load;
    ct.clearColor[3] = 1.0f;  // opaque black
    s.colorTargets.push(ct);
    if (depth) {
        s.depthTarget.view = wholeTexture(depth);
        s.depthTarget.load = load;
        s.depthTarget.clearDepth = 1.0f;
        s.depth.testEnable = true;
        s.depth.writeEnable = true;
        s.depth.compare = CompareOp::Less;
    }
    tweak(s);
    bool ok = d.draw(s, {uint32_t(verts.size()), 1, 0, 0});
    d.destroy(vb);
    return ok;
}

uint32_t pixel(const std::vector<uint8_t>& img, uint32_t w, uint32_t x, uint32_t row) {
    const uint8_t* p = &img[(row * w + x) * 4];
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3];
}
}  // namespace

TEST_CASE("gl: depth-tested draw, memory row 0 is clip y = -1", "[gl]") {
    IDevice& d = dev();
    const uint32_t W = 16, H = 16;
    TextureDesc cd;
    cd.width = W;
    cd.height = H;
    cd.usage = TextureUsage::RenderTarget | TextureUsage::Sampled;
    cd.debugName = "color";
    TextureHandle color = d.createTexture(cd);
    TextureDesc dd = cd;
    dd.format = Format::D32_FLOAT;
    dd.usage = TextureUsage::DepthTarget;
    dd.debugName = "depth";
    TextureHandle depth = d.createTexture(dd);
    REQUIRE((color && depth));

    // Red quad over clip y in [-1, 0] at z 0.5, then a green full-target quad at z 0.75: green only where
    // red is not (depth test Less against the red depth and the 1.0 clear).
    auto quad = [](float y0, float y1, float z, std::array<uint8_t, 4> c) {
        Vertex a{-1, y0, z, {c[0], c[1], c[2], c[3]}}, b{1, y0, z, {c[0], c[1], c[2], c[3]}},
            e{1, y1, z, {c[0], c[1], c[2], c[3]}}, f{-1, y1, z, {c[0], c[1], c[2], c[3]}};
        return std::vector<Vertex>{a, b, e, a, e, f};
    };
    REQUIRE(drawTriangles(d, quad(-1, 0, 0.5f, {255, 0, 0, 255}), color, depth, LoadOp::Clear, [](DrawCallState&) {}));
    REQUIRE(drawTriangles(d, quad(-1, 1, 0.75f, {0, 255, 0, 255}), color, depth, LoadOp::Load, [](DrawCallState&) {}));
    std::vector<uint8_t> img(W * H * 4);
    REQUIRE(d.readTexture(color, {}, img.data()));
    CHECK(pixel(img, W, 0, 0) == 0xFF0000FFu);       // row 0 = clip y -1: red
    CHECK(pixel(img, W, 15, 7) == 0xFF0000FFu);
    CHECK(pixel(img, W, 0, 8) == 0x00FF00FFu);       // upper half of clip space: green
    CHECK(pixel(img, W, 15, 15) == 0x00FF00FFu);
    std::vector<float> z(W * H);
    REQUIRE(d.readTexture(depth, {}, z.data()));
    CHECK(z[0] == Approx(0.5f));                     // depth range [0,1]: z_ndc written as is
    CHECK(z[15 * W] == Approx(0.75f));

    // Viewport + scissor: only the top-left 4x4 block of memory (rows 0..3) changes.
    REQUIRE(drawTriangles(d, quad(-1, 1, 0.0f, {0, 0, 255, 255}), color, TextureHandle{}, LoadOp::Load,
                          [](DrawCallState& s) {
                              s.viewport = {0, 0, 8, 8, 0, 1};
                              s.scissor = {0, 0, 4, 4};
                          }));
    REQUIRE(d.readTexture(color, {}, img.data()));
    CHECK(pixel(img, W, 0, 0) == 0x0000FFFFu);
    CHECK(pixel(img, W, 3, 3) == 0x0000FFFFu);
    CHECK(pixel(img, W, 4, 0) == 0xFF0000FFu);
    CHECK(pixel(img, W, 0, 4) == 0xFF0000FFu);
    CHECK(errors().empty());
    d.destroy(color);
    d.destroy(depth);
}

TEST_CASE("gl: culling follows Vulkan's winding rule", "[gl]") {
    IDevice& d = dev();
    TextureDesc cd;
    cd.width = cd.height = 8;
    cd.usage = TextureUsage::RenderTarget;
    TextureHandle color = d.createTexture(cd);
    // Counter-clockwise in clip space (x right, y up). Vulkan's framebuffer y grows with clip y and its
    // area formula has the opposite sign of GL's, so with frontFace = CounterClockwise this triangle is a
    // back face: culled with CullMode::Back, drawn with CullMode::Front, and its reverse the other way.
    std::vector<Vertex> ccwInClip = {{-1, -1, 0, {255, 255, 255, 255}}, {3, -1, 0, {255, 255, 255, 255}},
                                     {-1, 3, 0, {255, 255, 255, 255}}};
    std::vector<Vertex> cwInClip = {ccwInClip[0], ccwInClip[2], ccwInClip[1]};
    auto covered = [&](const std::vector<Vertex>& v, CullMode cull, FrontFace front) {
        REQUIRE(drawTriangles(d, v, color, TextureHandle{}, LoadOp::Clear, [&](DrawCallState& s) {
            s.raster.cull = cull;
            s.raster.frontFace = front;
        }));
        uint8_t px[8 * 8 * 4];
        REQUIRE(d.readTexture(color, {}, px));
        return px[4 * (3 * 8 + 3)] == 255;
    };
    CHECK_FALSE(covered(ccwInClip, CullMode::Back, FrontFace::CounterClockwise));
    CHECK(covered(ccwInClip, CullMode::Front, FrontFace::CounterClockwise));
    CHECK(covered(cwInClip, CullMode::Back, FrontFace::CounterClockwise));
    CHECK_FALSE(covered(cwInClip, CullMode::Back, FrontFace::Clockwise));
    CHECK(covered(ccwInClip, CullMode::None, FrontFace::CounterClockwise));
    CHECK(errors().empty());
    d.destroy(color);
}

TEST_CASE("gl: indirect dispatch with arguments written by a dispatch", "[gl]") {
    IDevice& d = dev();
    ShaderHandle writeArgs = shader("rhi_tests/smoke_gl_indirect_args.comp");
    ShaderHandle fill = shader("rhi_tests/smoke_gl_fill.comp");
    BufferHandle args = d.createBuffer({16, 0, BufferUsage::ShaderWrite | BufferUsage::IndirectArgs, "args"});
    BufferHandle out = d.createBuffer({512 * 4, 0, BufferUsage::ShaderWrite, "out"});
    REQUIRE(d.clearBuffer(out, {}, 0xFFFFFFFFu));
    uint32_t groups = 3;
    DispatchState w;
    w.shader = writeArgs;
    w.bindings.constants.push(constants(0, groups));
    w.bindings.storageBuffers.push({0, args, {0, 12}, Access::Write});
    REQUIRE(d.dispatch(w, 1, 1, 1));
    FillParams params{512, 1, 0};
    DispatchState f;
    f.shader = fill;
    f.bindings.constants.push(constants(0, params));
    f.bindings.storageBuffers.push({0, out, {}, Access::Write});
    const uint64_t before = gl::barrierCount(d).value();
    REQUIRE(d.dispatchIndirect(f, args, 0));
    CHECK(gl::barrierCount(d).value() == before + 1);  // COMMAND
    auto v = readU32(out, 512);
    CHECK(v[0] == 0);
    CHECK(v[191] == 191);           // 3 groups of 64
    CHECK(v[192] == 0xFFFFFFFFu);   // untouched
    CHECK(errors().empty());
    d.destroy(args);
    d.destroy(out);
}

TEST_CASE("gl: timestamps of nested markers", "[gl]") {
    IDevice& d = dev();
    REQUIRE(d.capabilities().timestamps);
    ShaderHandle fill = shader("rhi_tests/smoke_gl_fill.comp");
    BufferHandle out = d.createBuffer({4096 * 4, 0, BufferUsage::ShaderWrite, "out"});
    FillParams params{4096, 1, 0};
    DispatchState f;
    f.shader = fill;
    f.bindings.constants.push(constants(0, params));
    f.bindings.storageBuffers.push({0, out, {}, Access::Write});
    d.setTimingEnabled(true);
    d.beginMarker("frame");
    d.beginMarker("fill");
    REQUIRE(d.dispatch(f, 64, 1, 1));
    d.endMarker();
    d.endMarker();
    d.endFrame();
    d.waitIdle();
    auto timings = d.takeTimings();
    d.setTimingEnabled(false);
    REQUIRE(timings.size() == 2);
    CHECK(timings[0].label == "frame");
    CHECK(timings[1].label == "frame/fill");
    CHECK(timings[0].milliseconds >= timings[1].milliseconds);
    CHECK(timings[1].milliseconds >= 0.0);
    CHECK(d.takeTimings().empty());
    CHECK(errors().empty());
    d.destroy(out);
}

TEST_CASE("gl: bad calls report clear errors and change nothing", "[gl]") {
    IDevice& d = dev();
    ShaderHandle fill = shader("rhi_tests/smoke_gl_fill.comp");
    BufferHandle gone = d.createBuffer({256, 0, BufferUsage::ShaderWrite, "gone"});
    d.destroy(gone);
    FillParams params{64, 1, 0};
    DispatchState f;
    f.shader = fill;
    f.label = "bad";
    f.bindings.constants.push(constants(0, params));
    f.bindings.storageBuffers.push({0, gone, {}, Access::Write});
    CHECK_FALSE(d.dispatch(f, 1, 1, 1));
    REQUIRE(errors().size() == 1);
    CHECK(errors()[0].find("dispatch 'bad': storageBuffers[0] (slot 0)") != std::string::npos);
    CHECK(errors()[0].find("'gone'") != std::string::npos);
    CHECK(errors()[0].find("destroyed") != std::string::npos);

    errors().clear();
    BufferHandle big = d.createBuffer({4096, 0, BufferUsage::ShaderWrite, "big"});
    f.bindings.storageBuffers[0] = {0, big, {4, 64}, Access::Write};  // misaligned offset
    CHECK_FALSE(d.dispatch(f, 1, 1, 1));
    REQUIRE(errors().size() == 1);
    CHECK(errors()[0].find("GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT") != std::string::npos);

    errors().clear();
    f.bindings.storageBuffers.count = 0;  // the shader's Output block is left unbound
    CHECK_FALSE(d.dispatch(f, 1, 1, 1));
    REQUIRE(errors().size() == 1);
    CHECK(errors()[0].find("missing binding") != std::string::npos);

    errors().clear();
    TextureDesc srgb;
    srgb.format = Format::RGBA8_SRGB;
    srgb.usage = TextureUsage::Storage;
    CHECK_FALSE(d.createTexture(srgb));
    CHECK(errors().size() == 1);

    errors().clear();
    CHECK_FALSE(d.readBuffer(big, 4000, 100, nullptr));
    CHECK(errors().size() == 1);
    d.destroy(big);
}

TEST_CASE("gl: indexed, indirect indexed, geometry shader and sRGB draws", "[gl]") {
    IDevice& d = dev();
    const uint32_t W = 16;
    TextureDesc cd;
    cd.width = cd.height = W;
    cd.usage = TextureUsage::RenderTarget;
    TextureHandle color = d.createTexture(cd);
    cd.format = Format::RGBA8_SRGB;
    TextureHandle srgb = d.createTexture(cd);
    const uint8_t c = 128;
    std::vector<Vertex> quad = {{-1, -1, 0, {c, c, c, 255}}, {1, -1, 0, {c, c, c, 255}}, {1, 1, 0, {c, c, c, 255}},
                                {-1, 1, 0, {c, c, c, 255}}};
    BufferHandle vb = d.createBuffer({quad.size() * sizeof(Vertex), 0, BufferUsage::Vertex, "quad"}, quad.data());
    const uint16_t indices[] = {0xFFFF, 0xFFFF, 0, 1, 2, 0, 2, 3};  // the quad starts at byte offset 4
    BufferHandle ib = d.createBuffer({sizeof(indices), 0, BufferUsage::Index, "indices"}, indices);
    const uint32_t args[8] = {0, 0, 6, 1, 0, 0, 0, 0};  // DrawIndexedArgs at byte offset 8
    BufferHandle ab = d.createBuffer({sizeof(args), 0, BufferUsage::IndirectArgs, "drawArgs"}, args);
    REQUIRE((color && srgb && vb && ib && ab));

    DrawCallState s;
    s.vertexShader = shader("rhi_tests/smoke_gl_triangle.vert");
    s.fragmentShader = shader("rhi_tests/smoke_gl_triangle.frag");
    s.vertexInputs.push({0, VertexFormat::Float3, 0, 0});
    s.vertexInputs.push({1, VertexFormat::UByte4Norm, 0, 12});
    s.vertexBuffers.push({vb, 0, sizeof(Vertex), false});
    s.indexBuffer = {ib, 4, IndexFormat::U16};
    ColorTarget ct;
    ct.view = wholeTexture(color);
    ct.load = LoadOp::Clear;
    s.colorTargets.push(ct);
    std::vector<uint8_t> img(W * W * 4);
    auto coverage = [&](TextureHandle t) {
        REQUIRE(d.readTexture(t, {}, img.data()));
        int n = 0;
        for (uint32_t i = 0; i < W * W; ++i) n += img[i * 4] != 0;
        return n;
    };

    REQUIRE(d.drawIndexed(s, {6, 1, 0, 0, 0}));
    CHECK(coverage(color) == int(W * W));
    CHECK(int(img[0]) == 128);
    REQUIRE(d.drawIndexed(s, {3, 1, 0, 0, 0}));  // one triangle: half the target (+ the diagonal)
    CHECK(coverage(color) > int(W * W / 2) - int(W));
    CHECK(coverage(color) < int(W * W / 2) + int(W));
    REQUIRE(d.drawIndirect(s, ab, 8, true));  // index buffer offset 4 with an indirect indexed draw
    CHECK(coverage(color) == int(W * W));

    // sRGB target: 128/255 linear is encoded to ~188, as Vulkan writes sRGB attachments.
    s.colorTargets[0].view = wholeTexture(srgb);
    REQUIRE(d.drawIndexed(s, {6, 1, 0, 0, 0}));
    coverage(srgb);
    CHECK(int(img[0]) >= 187);
    CHECK(int(img[0]) <= 189);

    // Geometry shader: one point at (-0.5, -0.5) grows to a quad of half-size 0.25: pixels 2..5 of rows 2..5.
    DrawCallState g;
    g.vertexShader = shader("rhi_tests/draw_points.vert");
    g.geometryShader = shader("rhi_tests/draw_points_to_quads.geom");
    g.fragmentShader = shader("rhi_tests/draw_color.frag");
    g.topology = PrimitiveTopology::PointList;
    g.vertexInputs = s.vertexInputs;
    std::vector<Vertex> point = {{-0.5f, -0.5f, 0, {255, 255, 255, 255}}};
    BufferHandle pb = d.createBuffer({sizeof(Vertex), 0, BufferUsage::Vertex, "point"}, point.data());
    g.vertexBuffers.push({pb, 0, sizeof(Vertex), false});
    ct.view = wholeTexture(color);
    g.colorTargets.push(ct);
    struct {
        float halfSize[2];
    } gp{{0.25f, 0.25f}};
    g.bindings.constants.push(constants(0, gp));
    REQUIRE(d.draw(g, {1, 1, 0, 0}));
    CHECK(coverage(color) == 16);
    CHECK(img[(2 * W + 2) * 4] == 255);
    CHECK(img[(5 * W + 5) * 4] == 255);
    CHECK(img[(6 * W + 6) * 4] == 0);
    CHECK(errors().empty());
    for (BufferHandle h : {vb, ib, ab, pb}) d.destroy(h);
    d.destroy(color);
    d.destroy(srgb);
}
