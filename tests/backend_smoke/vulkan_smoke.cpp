// Smoke test of the Vulkan backend with VK_LAYER_KHRONOS_validation on: every test fails on any validation
// message. The conformance kit (tests/conformance) covers the contract in depth on every backend; this
// checks that the backend itself works: compute + read-back, storage image -> sampled read, a depth-tested
// draw checked pixel-exact, indirect dispatch with GPU-written args, barrier counts, timestamps, errors,
// embedded mode (application command buffer, descriptor-pool path).
#include <catch2/catch.hpp>

#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bricklight/rhi.h"
#include "bricklight/rhi_validation.h"
#include "bricklight/rhi_vulkan.h"
#include "hostile_sizes.h"

using namespace bricklight;
using namespace bricklight::rhi;

namespace {

struct Messages {
    std::vector<std::string> errors;      // the backend's own errors
    std::vector<std::string> validation;  // validation-layer messages
    void clear() { errors.clear(), validation.clear(); }
    bool errorContains(const std::string& s) const {
        for (const auto& e : errors)
            if (e.find(s) != std::string::npos) return true;
        return false;
    }
};

struct Fixture {
    std::shared_ptr<Messages> messages = std::make_shared<Messages>();
    std::unique_ptr<IDevice> device;

    explicit Fixture(bool disablePush = false, bool syncValidation = false, bool barrierReuse = true) {
        vulkan::DeviceOptions o;
        o.enableValidation = true;
        o.enableSyncValidation = syncValidation;
        o.preferSoftware = true;
        o.disablePushDescriptors = disablePush;
        o.disableBarrierReuse = !barrierReuse;
        auto m = messages;
        o.errorCallback = [m](Severity, const std::string& msg) {
            if (msg.rfind("vulkan validation: ", 0) == 0) {
                m->validation.push_back(msg);
                UNSCOPED_INFO(msg);
            } else {
                m->errors.push_back(msg);
            }
        };
        device = vulkan::createDevice(o);
        REQUIRE(device);
    }
    ~Fixture() {
        if (device) device->waitIdle();
        device.reset();
        for (const auto& v : messages->validation) UNSCOPED_INFO(v);
        CHECK(messages->validation.empty());
    }
    ShaderHandle shader(const char* name) {
        const ShaderBlob* blob = findShader(name);
        REQUIRE(blob);
        ShaderHandle h = device->createShader({blob, ""});
        REQUIRE(h);
        return h;
    }
};

std::vector<uint32_t> readU32(IDevice& d, BufferHandle b, size_t count) {
    std::vector<uint32_t> v(count);
    REQUIRE(d.readBuffer(b, 0, count * 4, v.data()));
    return v;
}

uint32_t rgba(uint8_t r, uint8_t g, uint8_t b, uint8_t a) { return r | (g << 8) | (b << 16) | (uint32_t(a) << 24); }

}  // namespace

// hostile_sizes.cpp runs on the bare backend with the validation layer on.
std::unique_ptr<smoke::HostileBackend> smoke::makeHostileBackend() {
    struct Vulkan final : HostileBackend {
        Fixture f;
        const char* name() const override { return "vulkan"; }
        IDevice& device() override { return *f.device; }
        std::vector<std::string> takeErrors() override { return std::exchange(f.messages->errors, {}); }
        std::vector<std::string> takeDriverMessages() override { return std::exchange(f.messages->validation, {}); }
    };
    return std::make_unique<Vulkan>();
}

TEST_CASE("vulkan: capabilities are reported", "[vulkan][smoke]") {
    Fixture f;
    const Capabilities& c = f.device->capabilities();
    CHECK(c.backendName == "vulkan");
    CHECK(!c.deviceName.empty());
    CHECK(c.limits.maxColorTargets >= 4);
    CHECK(c.limits.maxComputeGroupInvocations >= 128);
    CHECK(c.supports(Format::RGBA8_UNORM, FormatSupport::Sampled | FormatSupport::Storage | FormatSupport::RenderTarget));
    CHECK(c.supports(Format::R32_UINT, FormatSupport::StorageAtomic));
    CHECK(c.supports(Format::D32_FLOAT, FormatSupport::DepthTarget));
    CHECK(!c.supports(Format::R11G11B10_FLOAT, FormatSupport::Storage));
    CHECK(!c.supports(Format::RGBA8_SRGB, FormatSupport::Storage));
    CHECK(vulkan::nativeDevice(*f.device) != VK_NULL_HANDLE);
    CHECK(vulkan::barrierCount(*f.device).has_value());
    // A device that is not the backend's own (a wrapper around one, or here the null device) cannot tell:
    // the hooks say so instead of answering 0.
    std::unique_ptr<IDevice> foreign = createNullDevice();
    CHECK_FALSE(vulkan::barrierCount(*foreign).has_value());
    CHECK_FALSE(vulkan::pipelineBarrierCount(*foreign).has_value());
    CHECK_FALSE(vulkan::validationMessageCount(*foreign).has_value());
    CHECK_FALSE(vulkan::usesPushDescriptors(*foreign).has_value());
}

TEST_CASE("vulkan: compute fill and read-back", "[vulkan][smoke]") {
    Fixture f;
    IDevice& d = *f.device;
    BufferHandle buf = d.createBuffer({256 * 4, 4, BufferUsage::ShaderWrite, "fill"});
    REQUIRE(buf);
    struct {
        uint32_t count, scale, offset;
    } params{200, 3, 7};
    DispatchState ds;
    ds.shader = f.shader("rhi_tests/fill_buffer.comp");
    ds.bindings.constants.push(constants(0, params));
    ds.bindings.storageBuffers.push({0, buf, {}, Access::Write});
    ds.label = "fill";
    REQUIRE(d.dispatch(ds, 4, 1, 1));
    auto v = readU32(d, buf, 256);
    for (uint32_t i = 0; i < 256; ++i) REQUIRE(v[i] == (i < 200 ? i * 3 + 7 : 0u));  // new buffers read as zero

    // Constants are copied at call time: a second dispatch with other values in the same frame.
    params = {256, 1, 0};
    ds.bindings.constants[0] = constants(0, params);
    REQUIRE(d.dispatch(ds, 4, 1, 1));
    params = {0, 0, 0};  // changing the struct after the call must not matter
    v = readU32(d, buf, 256);
    for (uint32_t i = 0; i < 256; ++i) REQUIRE(v[i] == i);
    d.endFrame();
}

TEST_CASE("vulkan: storage image write then sampled read", "[vulkan][smoke]") {
    Fixture f;
    IDevice& d = *f.device;
    const uint32_t W = 20, H = 12;
    TextureDesc td;
    td.width = W, td.height = H, td.format = Format::RGBA8_UNORM;
    td.usage = TextureUsage::Storage | TextureUsage::Sampled;
    td.debugName = "pattern";
    TextureHandle tex = d.createTexture(td);
    REQUIRE(tex);
    DispatchState write;
    write.shader = f.shader("rhi_tests/smoke_vk_write_image.comp");
    write.bindings.storageImages.push({0, wholeTexture(tex), Access::Write});
    write.label = "write image";
    REQUIRE(d.dispatch(write, (W + 7) / 8, (H + 7) / 8, 1));

    SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = Filter::Nearest;
    SamplerHandle sampler = d.createSampler(sd);
    BufferHandle out = d.createBuffer({W * H * 4, 0, BufferUsage::ShaderWrite, "sampled"});
    struct {
        uint32_t w, h;
    } size{W, H};
    DispatchState read;
    read.shader = f.shader("rhi_tests/smoke_vk_sample.comp");
    read.bindings.constants.push(constants(0, size));
    read.bindings.textures.push({0, wholeTexture(tex), sampler});
    read.bindings.storageBuffers.push({0, out, {}, Access::Write});
    read.label = "sample image";
    REQUIRE(d.dispatch(read, (W + 7) / 8, (H + 7) / 8, 1));
    auto v = readU32(d, out, W * H);
    std::vector<uint32_t> direct(W * H);
    REQUIRE(d.readTexture(tex, {}, direct.data()));
    for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x) {
            const uint32_t expect = rgba(uint8_t(x), uint8_t(y), uint8_t(x + y), 255);
            REQUIRE(v[y * W + x] == expect);
            REQUIRE(direct[y * W + x] == expect);
        }
}

namespace {
struct Vertex {
    float x, y, z;
    uint8_t r, g, b, a;
};
}  // namespace

TEST_CASE("vulkan: depth-tested triangles, pixel-exact", "[vulkan][smoke]") {
    Fixture f;
    IDevice& d = *f.device;
    const uint32_t W = 32, H = 32;
    // A big red triangle at depth 0.5 drawn after a small green one at depth 0.25: the depth test keeps the
    // green one in front. Both are flat-coloured so that every covered pixel is exact.
    const Vertex verts[] = {
        {-0.5f, -0.5f, 0.25f, 0, 255, 0, 255}, {0.5f, -0.5f, 0.25f, 0, 255, 0, 255}, {0.0f, 0.5f, 0.25f, 0, 255, 0, 255},
        {-1.0f, -1.0f, 0.5f, 255, 0, 0, 255},  {3.0f, -1.0f, 0.5f, 255, 0, 0, 255},  {-1.0f, 0.0f, 0.5f, 255, 0, 0, 255},
    };
    BufferHandle vb = d.createBuffer({sizeof(verts), 0, BufferUsage::Vertex, "triangles"}, verts);
    TextureDesc ct;
    ct.width = W, ct.height = H, ct.format = Format::RGBA8_UNORM, ct.usage = TextureUsage::RenderTarget;
    ct.debugName = "color";
    TextureHandle color = d.createTexture(ct);
    TextureDesc dt = ct;
    dt.format = Format::D32_FLOAT, dt.usage = TextureUsage::DepthTarget, dt.debugName = "depth";
    TextureHandle depth = d.createTexture(dt);
    REQUIRE((vb && color && depth));

    DrawCallState s;
    s.vertexShader = f.shader("rhi_tests/smoke_vk_triangle.vert");
    s.fragmentShader = f.shader("rhi_tests/smoke_vk_triangle.frag");
    s.vertexInputs.push({0, VertexFormat::Float3, 0, 0});
    s.vertexInputs.push({1, VertexFormat::UByte4Norm, 0, 12});
    s.vertexBuffers.push({vb, 0, sizeof(Vertex), false});
    ColorTarget target;
    target.view = wholeTexture(color);
    target.load = LoadOp::Clear;
    s.colorTargets.push(target);
    s.depthTarget.view = wholeTexture(depth);
    s.depthTarget.load = LoadOp::Clear;
    s.depth = {true, true, CompareOp::Less};
    s.label = "green";
    REQUIRE(d.draw(s, {3, 1, 0, 0}));
    s.colorTargets[0].load = LoadOp::Load;
    s.depthTarget.load = LoadOp::Load;
    s.label = "red";
    REQUIRE(d.draw(s, {3, 1, 3, 0}));

    std::vector<uint32_t> px(W * H);
    REQUIRE(d.readTexture(color, {}, px.data()));
    const uint32_t black = rgba(0, 0, 0, 0), red = rgba(255, 0, 0, 255), green = rgba(0, 255, 0, 255);
    auto at = [&](uint32_t x, uint32_t y) { return px[y * W + x]; };
    CHECK(at(16, 16) == green);  // centre: both triangles, green is nearer
    CHECK(at(16, 9) == green);   // upper part of the green triangle (clip y -0.4 is memory row ~9)
    CHECK(at(2, 2) == red);      // top-left: only the red triangle (it covers clip y < 0 = rows 0..15)
    CHECK(at(30, 2) == red);
    CHECK(at(2, 30) == black);   // bottom rows: nothing drawn (clip y > 0)
    CHECK(at(30, 30) == black);
    std::vector<float> z(W * H);
    REQUIRE(d.readTexture(depth, {}, z.data()));
    CHECK(z[16 * W + 16] == 0.25f);
    CHECK(z[2 * W + 2] == 0.5f);
    CHECK(z[30 * W + 30] == 1.0f);

    SECTION("geometry shader replaces the colour") {
        if (!d.capabilities().geometryShader) return;
        s.geometryShader = f.shader("rhi_tests/smoke_vk_passthrough.geom");
        const float blue[4] = {0, 0, 1, 1};
        s.bindings.constants.push({0, blue, sizeof(blue)});
        s.depth = {false, false, CompareOp::Always};
        s.label = "geometry";
        REQUIRE(d.draw(s, {3, 1, 0, 0}));
        REQUIRE(d.readTexture(color, {}, px.data()));
        CHECK(at(16, 16) == rgba(0, 0, 255, 255));
        CHECK(at(2, 2) == red);
    }
    SECTION("indexed and indirect draws, scissor") {
        const uint16_t indices[] = {3, 4, 5};
        BufferHandle ib = d.createBuffer({sizeof(indices), 0, BufferUsage::Index, "indices"}, indices);
        const DrawArgs args{3, 1, 0, 0};
        BufferHandle argsBuf = d.createBuffer({sizeof(args), 0, BufferUsage::IndirectArgs, "draw args"}, &args);
        s.indexBuffer = {ib, 0, IndexFormat::U16};
        s.colorTargets[0].load = LoadOp::Clear;
        s.depth = {false, false, CompareOp::Always};
        s.scissor = {0, 0, 8, 8};
        REQUIRE(d.drawIndexed(s, {3, 1, 0, 0, 0}));  // red, only inside the scissor
        REQUIRE(d.readTexture(color, {}, px.data()));
        CHECK(at(2, 2) == red);
        CHECK(at(12, 2) == black);
        s.colorTargets[0].load = LoadOp::Load;
        s.scissor = {};
        REQUIRE(d.drawIndirect(s, argsBuf, 0, false));  // green triangle
        REQUIRE(d.readTexture(color, {}, px.data()));
        CHECK(at(16, 16) == green);
        CHECK(at(12, 2) == black);
    }
}

TEST_CASE("vulkan: indirect dispatch with GPU-written args, atomics, barrier counts", "[vulkan][smoke]") {
    Fixture f;
    IDevice& d = *f.device;
    BufferHandle args = d.createBuffer({12, 0, BufferUsage::ShaderWrite | BufferUsage::IndirectArgs, "args"});
    BufferHandle counter = d.createBuffer({4, 0, BufferUsage::ShaderWrite, "counter"});
    const uint32_t one = 1;
    BufferHandle addend = d.createBuffer({4, 0, BufferUsage::ShaderRead, "addend"}, &one);
    struct {
        uint32_t groups;
    } params{5};
    DispatchState writeArgs;
    writeArgs.shader = f.shader("rhi_tests/smoke_vk_write_args.comp");
    writeArgs.bindings.constants.push(constants(0, params));
    writeArgs.bindings.storageBuffers.push({0, args, {}, Access::Write});
    writeArgs.label = "write args";
    REQUIRE(d.dispatch(writeArgs, 1, 1, 1));
    DispatchState count;
    count.shader = f.shader("rhi_tests/smoke_vk_count.comp");
    count.bindings.readBuffers.push({0, addend, {}});
    count.bindings.storageBuffers.push({0, counter, {}, Access::Atomic});
    count.label = "count";
    REQUIRE(d.dispatchIndirect(count, args, 0));
    CHECK(readU32(d, counter, 1)[0] == 5 * 64);
    CHECK(readU32(d, args, 3) == std::vector<uint32_t>{5, 1, 1});

    // Read-after-read: a second reader of `addend` and `args` needs no barrier for them; the counter
    // (atomic, read-write) still needs one against the previous dispatch unless the flag says otherwise.
    REQUIRE(d.dispatchIndirect(count, args, 0));
    uint64_t before = vulkan::barrierCount(d).value();
    REQUIRE(d.dispatchIndirect(count, args, 0));
    CHECK(vulkan::barrierCount(d).value() - before == 1);  // counter only (write after write)
    count.flags = DispatchFlags::NoBarrierWithPreviousWriter;
    before = vulkan::barrierCount(d).value();
    REQUIRE(d.dispatchIndirect(count, args, 0));
    CHECK(vulkan::barrierCount(d).value() - before == 0);
    CHECK(readU32(d, counter, 1)[0] == 4 * 5 * 64);

    // Pure read-after-read on a buffer that was last written long ago: zero barriers.
    DispatchState fill;
    BufferHandle sink1 = d.createBuffer({4, 0, BufferUsage::ShaderWrite, "sink1"});
    fill.shader = count.shader;
    fill.bindings.readBuffers.push({0, addend, {}});
    fill.bindings.storageBuffers.push({0, sink1, {}, Access::Atomic});
    REQUIRE(d.dispatch(fill, 1, 1, 1));
    fill.flags = DispatchFlags::NoBarrierWithPreviousWriter;
    before = vulkan::barrierCount(d).value();
    REQUIRE(d.dispatch(fill, 1, 1, 1));
    CHECK(vulkan::barrierCount(d).value() - before == 0);
    CHECK(readU32(d, sink1, 1)[0] == 128);
}

TEST_CASE("vulkan: a hazard an earlier barrier already ordered needs no barrier", "[vulkan][smoke]") {
    // New buffers start cleared by a transfer, so each first write has a hazard: with reuse the first
    // write's barrier is global and takes in everything outstanding (the other buffer's clear too), so
    // the second write needs none. Then a reader of each: the first reader's barrier takes in both writes,
    // so the second reader needs none. A rewrite after both readers needs one (they ran after the last
    // barrier). Without reuse every hazard gets its own barrier. Synchronization validation checks that
    // what was left out was not needed.
    for (const bool reuse : {true, false}) {
        CAPTURE(reuse);
        Fixture f(false, true, reuse);
        IDevice& d = *f.device;
        BufferHandle x = d.createBuffer({4, 0, BufferUsage::ShaderRead | BufferUsage::ShaderWrite, "x"});
        BufferHandle y = d.createBuffer({4, 0, BufferUsage::ShaderRead | BufferUsage::ShaderWrite, "y"});
        BufferHandle sumX = d.createBuffer({4, 0, BufferUsage::ShaderWrite, "sumX"});
        BufferHandle sumY = d.createBuffer({4, 0, BufferUsage::ShaderWrite, "sumY"});
        d.waitIdle();
        const ShaderHandle fill = f.shader("rhi_tests/fill_buffer.comp");
        const ShaderHandle count = f.shader("rhi_tests/smoke_vk_count.comp");
        auto write = [&](BufferHandle target, uint32_t value) {
            struct {
                uint32_t count, scale, offset;
            } params{1, 0, value};
            DispatchState s;
            s.shader = fill;
            s.bindings.constants.push(constants(0, params));
            s.bindings.storageBuffers.push({0, target, {}, Access::Write});
            REQUIRE(d.dispatch(s, 1, 1, 1));
        };
        auto sum = [&](BufferHandle source, BufferHandle total) {
            DispatchState s;
            s.shader = count;
            s.bindings.readBuffers.push({0, source, {}});
            s.bindings.storageBuffers.push({0, total, {}, Access::Atomic});
            REQUIRE(d.dispatch(s, 1, 1, 1));
        };
        const uint64_t start = vulkan::pipelineBarrierCount(d).value();
        write(x, 7);
        write(y, 5);
        CHECK(vulkan::pipelineBarrierCount(d).value() - start == (reuse ? 1u : 2u));
        sum(x, sumX);
        CHECK(vulkan::pipelineBarrierCount(d).value() - start == (reuse ? 2u : 3u));
        sum(y, sumY);
        CHECK(vulkan::pipelineBarrierCount(d).value() - start == (reuse ? 2u : 4u));
        write(x, 1);  // write after the readers: one execution dependency
        CHECK(vulkan::pipelineBarrierCount(d).value() - start == (reuse ? 3u : 5u));
        CHECK(readU32(d, sumX, 1)[0] == 64 * 7);
        CHECK(readU32(d, sumY, 1)[0] == 64 * 5);
        CHECK(readU32(d, x, 1)[0] == 1);
    }
}

TEST_CASE("vulkan: timestamps for nested markers", "[vulkan][smoke]") {
    Fixture f;
    IDevice& d = *f.device;
    REQUIRE(d.capabilities().timestamps);
    d.setTimingEnabled(true);
    BufferHandle buf = d.createBuffer({64 * 4, 0, BufferUsage::ShaderWrite, "timed"});
    struct {
        uint32_t count, scale, offset;
    } params{64, 1, 0};
    DispatchState ds;
    ds.shader = f.shader("rhi_tests/fill_buffer.comp");
    ds.bindings.constants.push(constants(0, params));
    ds.bindings.storageBuffers.push({0, buf, {}, Access::Write});
    d.beginMarker("frame");
    d.beginMarker("fill");
    REQUIRE(d.dispatch(ds, 1, 1, 1));
    d.endMarker();
    d.endMarker();
    d.endFrame();
    d.waitIdle();
    auto timings = d.takeTimings();
    REQUIRE(timings.size() == 2);
    bool inner = false, outer = false;
    for (const auto& t : timings) {
        CHECK(t.milliseconds >= 0.0);
        inner |= t.label == "frame/fill";
        outer |= t.label == "frame";
    }
    CHECK(inner);
    CHECK(outer);
    CHECK(d.takeTimings().empty());
}

TEST_CASE("vulkan: bad input is rejected with a clear message and changes nothing", "[vulkan][smoke]") {
    Fixture f;
    IDevice& d = *f.device;
    TextureDesc td;
    td.format = Format::R11G11B10_FLOAT, td.usage = TextureUsage::Storage, td.debugName = "hdr";
    CHECK(!d.createTexture(td));
    CHECK(f.messages->errorContains("createTexture 'hdr': format R11G11B10_FLOAT does not support Storage"));

    BufferHandle buf = d.createBuffer({64, 0, BufferUsage::ShaderWrite, "victim"});
    d.destroy(buf);
    CHECK(d.describe(buf) == nullptr);
    DispatchState ds;
    ds.shader = f.shader("rhi_tests/fill_buffer.comp");
    struct {
        uint32_t a, b, c;
    } params{1, 1, 1};
    ds.bindings.constants.push(constants(0, params));
    ds.bindings.storageBuffers.push({0, buf, {}, Access::Write});
    ds.label = "stale";
    f.messages->clear();
    CHECK(!d.dispatch(ds, 1, 1, 1));
    CHECK(f.messages->errorContains("dispatch 'stale': storageBuffers[0] (slot 0): buffer: buffer handle"));
    CHECK(f.messages->errorContains("was destroyed"));

    ds.bindings.storageBuffers.count = 0;
    CHECK(!d.dispatch(ds, 1, 1, 1));
    CHECK(f.messages->errorContains("declare storageBuffers slot 0 ('Output') but the record binds none"));

    BufferHandle small = d.createBuffer({64, 0, BufferUsage::ShaderWrite, "small"});
    CHECK(!d.readBuffer(small, 32, 64, std::vector<uint8_t>(64).data()));
    CHECK(!d.clearBuffer(small, {2, 4}, 0));
    CHECK(!d.copyBuffer(small, 0, small, 8, 16));
    TextureDesc good;
    good.width = 4, good.height = 4, good.usage = TextureUsage::Sampled, good.debugName = "t";
    TextureHandle t = d.createTexture(good);
    CHECK(!d.readTexture(t, {1, 0, 0}, std::vector<uint8_t>(64).data()));
    CHECK(!d.clearTexture(t, 0, 2, ClearValue{}));
    CHECK(d.describe(t) != nullptr);
    CHECK(f.messages->errors.size() >= 5);

    // More bad input the backend must survive without a crash or a validation message.
    f.messages->clear();
    CHECK(!d.createBuffer({0, 0, BufferUsage::ShaderRead, "empty"}));
    CHECK(!d.createShader({nullptr, "none"}));
    TextureDesc cube;
    cube.dimension = TextureDimension::TextureCube, cube.width = 4, cube.height = 8, cube.depthOrLayers = 6;
    CHECK(!d.createTexture(cube));
    TextureDesc srgb;
    srgb.width = srgb.height = 4, srgb.format = Format::RGBA8_SRGB, srgb.debugName = "srgb";
    srgb.usage = TextureUsage::Storage | TextureUsage::Sampled;
    TextureHandle srgbTex = d.createTexture(srgb);
    CHECK(srgbTex);  // storage through UNORM views
    DispatchState img;
    img.shader = f.shader("rhi_tests/smoke_vk_write_image.comp");
    img.bindings.storageImages.push({0, wholeTexture(srgbTex), Access::Write});
    CHECK(!d.dispatch(img, 1, 1, 1));
    CHECK(f.messages->errorContains("bind an RGBA8_UNORM view"));
    img.bindings.storageImages[0].view.format = Format::RGBA8_UNORM;
    CHECK(d.dispatch(img, 1, 1, 1));
    img.bindings.storageImages[0].view.baseMip = 3;
    CHECK(!d.dispatch(img, 1, 1, 1));
    DispatchState wrongStage;
    wrongStage.shader = f.shader("rhi_tests/smoke_vk_triangle.vert");
    CHECK(!d.dispatch(wrongStage, 1, 1, 1));
    CHECK(!d.writeTexture(t, {0, 1, 1}, std::vector<uint8_t>(64).data()));
    DrawCallState s;
    s.vertexShader = f.shader("rhi_tests/smoke_vk_triangle.vert");
    s.fragmentShader = f.shader("rhi_tests/smoke_vk_triangle.frag");
    CHECK(!d.draw(s, {3, 1, 0, 0}));  // no targets
    TextureDesc rt;
    rt.width = rt.height = 4, rt.usage = TextureUsage::RenderTarget, rt.debugName = "rt";
    TextureHandle rtTex = d.createTexture(rt);
    ColorTarget ct;
    ct.view = wholeTexture(rtTex);
    s.colorTargets.push(ct);
    CHECK(!d.draw(s, {3, 1, 0, 0}));  // the shader reads locations 0 and 1: no vertex inputs
    INFO(f.messages->errors.back());
    CHECK(f.messages->errorContains("but vertexInputs has none"));
    d.destroy(rtTex);
    d.destroy(rtTex);  // twice: reported, harmless
    CHECK(!d.draw(s, {3, 1, 0, 0}));
    CHECK(!d.drawIndirect(s, BufferHandle{9999}, 0, false));
    CHECK(f.messages->errorContains("was destroyed"));
    CHECK(f.messages->errors.size() >= 10);
}

TEST_CASE("vulkan: embedded mode records into the application's command buffer", "[vulkan][smoke]") {
    Fixture owner;  // provides the instance, device and queue the "application" owns
    vulkan::EmbeddedDesc e;
    e.instance = vulkan::nativeInstance(*owner.device);
    e.physicalDevice = vulkan::nativePhysicalDevice(*owner.device);
    e.device = vulkan::nativeDevice(*owner.device);
    e.queue = vulkan::nativeQueue(*owner.device);
    e.queueFamilyIndex = vulkan::nativeQueueFamily(*owner.device);
    auto messages = owner.messages;
    e.errorCallback = [messages](Severity, const std::string& m) { messages->errors.push_back(m); };
    auto dev = vulkan::createEmbeddedDevice(e);  // no push descriptors: exercises the descriptor-pool path
    REQUIRE(dev);
    CHECK_FALSE(vulkan::usesPushDescriptors(*dev).value());
    IDevice& d = *dev;

    VkDevice vk = e.device;
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.queueFamilyIndex = e.queueFamilyIndex;
    VkCommandPool pool;
    REQUIRE(vkCreateCommandPool(vk, &pci, nullptr, &pool) == VK_SUCCESS);
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool, ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY, ai.commandBufferCount = 1;
    VkCommandBuffer cb;
    REQUIRE(vkAllocateCommandBuffers(vk, &ai, &cb) == VK_SUCCESS);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    REQUIRE(vkBeginCommandBuffer(cb, &bi) == VK_SUCCESS);

    BufferHandle buf = d.createBuffer({128 * 4, 0, BufferUsage::ShaderWrite, "embedded"});
    vulkan::setCommandBuffer(d, cb);
    struct {
        uint32_t count, scale, offset;
    } params{128, 2, 1};
    DispatchState ds;
    ds.shader = d.createShader({findShader("rhi_tests/fill_buffer.comp"), ""});
    ds.bindings.constants.push(constants(0, params));
    ds.bindings.storageBuffers.push({0, buf, {}, Access::Write});
    REQUIRE(d.dispatch(ds, 2, 1, 1));
    std::vector<uint32_t> v(128);
    CHECK(!d.readBuffer(buf, 0, 512, v.data()));  // refused while the application's buffer is set
    REQUIRE(vkEndCommandBuffer(cb) == VK_SUCCESS);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1, si.pCommandBuffers = &cb;
    REQUIRE(vkQueueSubmit(e.queue, 1, &si, VK_NULL_HANDLE) == VK_SUCCESS);
    d.endFrame();
    vulkan::setCommandBuffer(d, VK_NULL_HANDLE);
    REQUIRE(d.readBuffer(buf, 0, 512, v.data()));
    for (uint32_t i = 0; i < 128; ++i) REQUIRE(v[i] == i * 2 + 1);
    d.waitIdle();
    dev.reset();
    vkDestroyCommandPool(vk, pool, nullptr);
}

TEST_CASE("vulkan: wrapped native buffer and image", "[vulkan][smoke]") {
    Fixture f;
    IDevice& d = *f.device;
    VkDevice vk = vulkan::nativeDevice(d);
    VkPhysicalDeviceMemoryProperties mp;
    vkGetPhysicalDeviceMemoryProperties(vulkan::nativePhysicalDevice(d), &mp);
    auto allocate = [&](VkMemoryRequirements req) {
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
            if (req.memoryTypeBits & (1u << i)) {
                ai.memoryTypeIndex = i;
                break;
            }
        VkDeviceMemory m = VK_NULL_HANDLE;
        REQUIRE(vkAllocateMemory(vk, &ai, nullptr, &m) == VK_SUCCESS);
        return m;
    };
    // The application's buffer and image (image left in UNDEFINED: aux 0 means "no layout to return to").
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = 64 * 4;
    bci.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer vkBuffer;
    REQUIRE(vkCreateBuffer(vk, &bci, nullptr, &vkBuffer) == VK_SUCCESS);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(vk, vkBuffer, &req);
    VkDeviceMemory bufferMemory = allocate(req);
    vkBindBufferMemory(vk, vkBuffer, bufferMemory, 0);
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.imageType = VK_IMAGE_TYPE_2D;
    ici.format = VK_FORMAT_R8G8B8A8_UNORM;
    ici.extent = {8, 8, 1};
    ici.mipLevels = ici.arrayLayers = 1;
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImage vkImage;
    REQUIRE(vkCreateImage(vk, &ici, nullptr, &vkImage) == VK_SUCCESS);
    vkGetImageMemoryRequirements(vk, vkImage, &req);
    VkDeviceMemory imageMemory = allocate(req);
    vkBindImageMemory(vk, vkImage, imageMemory, 0);

    BufferHandle buf = d.wrapNativeBuffer({64 * 4, 0, BufferUsage::ShaderWrite, "app buffer"},
                                          {reinterpret_cast<uint64_t>(vkBuffer), 0});
    TextureDesc td;
    td.width = td.height = 8, td.usage = TextureUsage::Storage, td.debugName = "app image";
    TextureHandle tex = d.wrapNativeTexture(td, {reinterpret_cast<uint64_t>(vkImage), 0});
    REQUIRE((buf && tex));
    struct {
        uint32_t count, scale, offset;
    } params{64, 2, 3};
    DispatchState fill;
    fill.shader = f.shader("rhi_tests/fill_buffer.comp");
    fill.bindings.constants.push(constants(0, params));
    fill.bindings.storageBuffers.push({0, buf, {}, Access::Write});
    REQUIRE(d.dispatch(fill, 1, 1, 1));
    DispatchState write;
    write.shader = f.shader("rhi_tests/smoke_vk_write_image.comp");
    write.bindings.storageImages.push({0, wholeTexture(tex), Access::Write});
    REQUIRE(d.dispatch(write, 1, 1, 1));
    auto v = readU32(d, buf, 64);
    for (uint32_t i = 0; i < 64; ++i) REQUIRE(v[i] == i * 2 + 3);
    std::vector<uint32_t> px(64);
    REQUIRE(d.readTexture(tex, {}, px.data()));
    CHECK(px[3 * 8 + 5] == rgba(5, 3, 8, 255));
    d.destroy(buf);
    d.destroy(tex);
    d.waitIdle();  // wrapped objects are forgotten, not freed: the application frees them
    vkDestroyBuffer(vk, vkBuffer, nullptr);
    vkDestroyImage(vk, vkImage, nullptr);
    vkFreeMemory(vk, bufferMemory, nullptr);
    vkFreeMemory(vk, imageMemory, nullptr);
}

TEST_CASE("vulkan: descriptor-pool fallback path", "[vulkan][smoke]") {
    Fixture f(/*disablePush=*/true);
    IDevice& d = *f.device;
    CHECK_FALSE(vulkan::usesPushDescriptors(d).value());
    BufferHandle buf = d.createBuffer({64 * 4, 0, BufferUsage::ShaderWrite, "fill"});
    struct {
        uint32_t count, scale, offset;
    } params{64, 5, 1};
    DispatchState ds;
    ds.shader = f.shader("rhi_tests/fill_buffer.comp");
    ds.bindings.constants.push(constants(0, params));
    ds.bindings.storageBuffers.push({0, buf, {}, Access::Write});
    for (int frame = 0; frame < 4; ++frame) {
        REQUIRE(d.dispatch(ds, 1, 1, 1));
        d.endFrame();
    }
    auto v = readU32(d, buf, 64);
    for (uint32_t i = 0; i < 64; ++i) REQUIRE(v[i] == i * 5 + 1);
}
