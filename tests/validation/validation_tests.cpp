// The validation wrapper's rejections, one test each, on the null device: each bad call gets a clear
// message naming the object and field, nothing reaches the inner device, and the device stays usable.
#include <catch2/catch.hpp>

#include <chrono>
#include <sstream>

#include "bricklight/rhi_validation.h"

using namespace bricklight::rhi;

namespace {

// Null device under a recorder under the validation wrapper: the recording shows what was forwarded.
struct Fixture {
    std::unique_ptr<IDevice> null = createNullDevice();
    std::stringstream forwarded;
    std::unique_ptr<IDevice> recorder = createRecordingDevice(*null, forwarded);
    std::unique_ptr<IDevice> device = createValidationDevice(*recorder);
    std::vector<std::string> errors, warnings;

    TextureHandle source, target, small3d;
    BufferHandle weights, counters, args;
    SamplerHandle sampler;
    ShaderHandle probe;
    float scale[4] = {1, 1, 1, 1};

    Fixture() {
        device->setErrorCallback([this](Severity s, const std::string& m) {
            (s == Severity::Error ? errors : warnings).push_back(m);
        });
        TextureDesc t;
        t.width = t.height = 16;
        t.format = Format::RGBA8_UNORM;
        t.mipLevels = 2;
        t.usage = TextureUsage::Sampled | TextureUsage::Storage;
        t.debugName = "source";
        source = device->createTexture(t);
        t.format = Format::RGBA16_FLOAT;
        t.debugName = "target";
        target = device->createTexture(t);
        BufferDesc b;
        b.size = 256;
        b.debugName = "weights";
        weights = device->createBuffer(b);
        b.debugName = "counters";
        counters = device->createBuffer(b);
        b.usage = BufferUsage::IndirectArgs;
        b.debugName = "args";
        args = device->createBuffer(b);
        SamplerDesc s;
        s.debugName = "linear";
        sampler = device->createSampler(s);
        probe = device->createShader({findShader("rhi_tests/validation_probe.comp"), ""});
        REQUIRE(errors.empty());
        REQUIRE(probe);
    }

    DispatchState good() const {
        DispatchState s;
        s.shader = probe;
        s.label = "probe";
        s.bindings.constants.push(ConstantsBinding{0, scale, sizeof(scale)});
        s.bindings.textures.push(TextureBinding{0, wholeTexture(source), sampler});
        s.bindings.readBuffers.push(ReadBufferBinding{0, weights, {}});
        s.bindings.storageBuffers.push(StorageBufferBinding{0, counters, {}, Access::Atomic});
        s.bindings.storageImages.push(StorageImageBinding{0, textureMip(target, 0), Access::Write});
        return s;
    }

    size_t forwardedLines() const {
        std::string all = forwarded.str();
        return size_t(std::count(all.begin(), all.end(), '\n'));
    }

    // Runs a bad call; requires that it fails, names `needle`, forwards nothing, and that a good dispatch
    // still goes through afterwards.
    template <typename F>
    void expectRejected(F&& badCall, const std::string& needle) {
        errors.clear();
        size_t before = forwardedLines();
        bool ok = badCall();
        CHECK_FALSE(ok);
        REQUIRE_FALSE(errors.empty());
        INFO("message: " << errors.front());
        CHECK(errors.front().find(needle) != std::string::npos);
        CHECK(forwardedLines() == before);
        errors.clear();
        CHECK(device->dispatch(good(), 2, 2, 1));
        CHECK(errors.empty());
        CHECK(forwardedLines() == before + 1);
    }
};

}  // namespace

TEST_CASE("a complete record passes and is forwarded", "[validation]") {
    Fixture f;
    CHECK(f.device->dispatch(f.good(), 2, 2, 1));
    CHECK(f.errors.empty());
    CHECK(f.warnings.empty());
}

TEST_CASE("a slot the source declares but does not use may be bound; one it never declares warns", "[validation]") {
    Fixture f;
    DispatchState s = f.good();
    s.bindings.readBuffers.push(ReadBufferBinding{3, f.weights, {}});  // declared, dropped as unused
    CHECK(f.device->dispatch(s, 1, 1, 1));
    CHECK(f.errors.empty());
    CHECK(f.warnings.empty());
    s.bindings.readBuffers.push(ReadBufferBinding{5, f.weights, {}});  // never declared
    CHECK(f.device->dispatch(s, 1, 1, 1));
    CHECK(f.errors.empty());
    REQUIRE(f.warnings.size() == 1);
    CHECK(f.warnings[0].find("readBuffers[2] (slot 5): shader rhi_tests/validation_probe.comp declares no read buffer at this slot") !=
          std::string::npos);
}

TEST_CASE("missing binding is rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.bindings.readBuffers.count = 0;
        return f.device->dispatch(s, 1, 1, 1);
    }, "missing binding: shader declares read buffer 'Weights' at slot 0");
}

TEST_CASE("binding of the wrong class is rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        DispatchState s = f.good();
        // The texture goes into the storage-image array instead of the texture array.
        s.bindings.textures.count = 0;
        s.bindings.storageImages.count = 0;
        s.bindings.storageImages.push(StorageImageBinding{0, textureMip(f.target, 0), Access::Write});
        s.bindings.storageImages.push(StorageImageBinding{1, textureMip(f.source, 0), Access::Read});
        return f.device->dispatch(s, 1, 1, 1);
    }, "missing binding: shader declares texture 'source' at slot 0");
    CHECK_FALSE(f.warnings.empty());
    CHECK(f.warnings.back().find("declares no storage image at this slot") != std::string::npos);
}

TEST_CASE("wrong format for a storage image is rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.bindings.storageImages[0].view = textureMip(f.source, 0);  // RGBA8 where the shader says rgba16f
        s.bindings.textures[0].view = textureMip(f.target, 1);
        return f.device->dispatch(s, 1, 1, 1);
    }, "wrong format for a storage image: shader 'target' declares RGBA16_FLOAT but the view is RGBA8_UNORM");
}

TEST_CASE("out-of-range buffer view is rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.bindings.readBuffers[0].range = BufferRange{128, 256};
        return f.device->dispatch(s, 1, 1, 1);
    }, "readBuffers[0] (slot 0) buffer 'weights': out-of-range buffer view [128, 384) of a 256-byte buffer");
}

TEST_CASE("mip out of range is rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.bindings.storageImages[0].view = textureMip(f.target, 5);
        return f.device->dispatch(s, 1, 1, 1);
    }, "storageImages[0] (slot 0) texture 'target': mip range 5+1 out of range (texture 'target' has 2 mips)");
}

TEST_CASE("zero-size resources are rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        TextureDesc t;
        t.width = 0;
        t.debugName = "empty";
        return bool(f.device->createTexture(t));
    }, "createTexture 'empty': zero-size texture (0x1x1)");
    f.expectRejected([&] {
        BufferDesc b;
        b.size = 0;
        b.debugName = "nothing";
        return bool(f.device->createBuffer(b));
    }, "createBuffer 'nothing': zero-size buffer");
}

TEST_CASE("group count over the limit is rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        return f.device->dispatch(f.good(), f.device->capabilities().limits.maxComputeGroupCount[0] + 1, 1, 1);
    }, "group count 65536 in dimension x exceeds maxComputeGroupCount 65535");
}

TEST_CASE("null shader is rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] { return bool(f.device->createShader({nullptr, "missing"})); },
                     "null shader: ShaderDesc::blob is null");
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.shader = ShaderHandle{};
        return f.device->dispatch(s, 1, 1, 1);
    }, "dispatch 'probe' (shader '?'): shader: null shader handle");
}

TEST_CASE("the same subresource bound for read and write is rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.bindings.textures[0].view = wholeTexture(f.target);  // sampled mips 0-1 while mip 0 is written
        return f.device->dispatch(s, 1, 1, 1);
    }, "the same subresource is bound for read and write: textures[0] (slot 0) texture 'target' and storageImages[0]");
    // Different mips of one texture are fine.
    DispatchState s = f.good();
    s.bindings.textures[0].view = textureMip(f.target, 1);
    f.errors.clear();
    CHECK(f.device->dispatch(s, 1, 1, 1));
    CHECK(f.errors.empty());
}

TEST_CASE("a destroyed handle is rejected", "[validation]") {
    Fixture f;
    BufferDesc b;
    b.size = 64;
    b.debugName = "doomed";
    BufferHandle doomed = f.device->createBuffer(b);
    f.device->destroy(doomed);
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.bindings.readBuffers[0].buffer = doomed;
        return f.device->dispatch(s, 1, 1, 1);
    }, "readBuffers[0] (slot 0).buffer: buffer 'doomed' (#" + std::to_string(doomed.id) + ") was destroyed");
    f.expectRejected([&] { return f.device->writeBuffer(doomed, 0, f.scale, 16); }, "was destroyed");
}

TEST_CASE("further record checks", "[validation]") {
    Fixture f;
    SECTION("constants smaller than the block") {
        f.expectRejected([&] {
            DispatchState s = f.good();
            s.bindings.constants[0].size = 8;
            return f.device->dispatch(s, 1, 1, 1);
        }, "8 bytes given but block 'Params' is 16 bytes");
    }
    SECTION("usage missing") {
        f.expectRejected([&] {
            DispatchState s = f.good();
            s.bindings.readBuffers[0].buffer = f.args;
            return f.device->dispatch(s, 1, 1, 1);
        }, "was not created with BufferUsage::ShaderRead");
    }
    SECTION("indirect args without IndirectArgs usage") {
        f.expectRejected([&] { return f.device->dispatchIndirect(f.good(), f.counters, 0); },
                         "lacks BufferUsage::IndirectArgs");
    }
    SECTION("non-storage format for a storage texture") {
        f.expectRejected([&] {
            TextureDesc t;
            t.format = Format::R11G11B10_FLOAT;
            t.usage = TextureUsage::Storage;
            t.debugName = "packed";
            return bool(f.device->createTexture(t));
        }, "createTexture 'packed': format R11G11B10_FLOAT does not support Storage");
    }
    SECTION("duplicate slot") {
        f.expectRejected([&] {
            DispatchState s = f.good();
            s.bindings.readBuffers.push(ReadBufferBinding{0, f.weights, {}});
            return f.device->dispatch(s, 1, 1, 1);
        }, "readBuffers[0] and [1] both bind slot 0");
    }
}

TEST_CASE("a recording replays on another device", "[validation]") {
    Fixture f;
    CHECK(f.device->dispatch(f.good(), 2, 2, 1));
    auto target = createNullDevice();
    std::stringstream in(f.forwarded.str());
    ReplayStats stats;
    std::string error;
    REQUIRE(replayRecording(in, *target, &stats, &error));
    CHECK(stats.calls == f.forwardedLines());
    CHECK(stats.failedCalls == 0);
    std::stringstream broken("{\"call\":\"dispatch\",\"state\":{}}\n");
    CHECK_FALSE(replayRecording(broken, *target, &stats, &error));
    CHECK(error.find("recording line 1") != std::string::npos);
}

TEST_CASE("sizes of 2^31 and more are rejected in bounded time, and ranges do not wrap", "[validation]") {
    Fixture f;
    const auto start = std::chrono::steady_clock::now();
    // The mip count was found by shifting the largest extent until it reached zero: a width or height of 2^31
    // or more needed a shift by 32, which x86 performs as a shift by 0, and the wrapper looped forever.
    for (uint32_t big : {1u << 31, 0xFFFFFFFFu}) {
        f.expectRejected([&] {
            TextureDesc t;
            t.width = big;
            t.debugName = "wide";
            return bool(f.device->createTexture(t));
        }, "createTexture 'wide': size " + std::to_string(big) + "x1 exceeds maxTextureSize2D");
        f.expectRejected([&] {
            TextureDesc t;
            t.height = big;
            t.mipLevels = 40;
            t.debugName = "tall";
            return bool(f.device->createTexture(t));
        }, "exceeds maxTextureSize2D");
        f.expectRejected([&] {
            TextureDesc t;
            t.dimension = TextureDimension::Texture3D;
            t.depthOrLayers = big;
            t.debugName = "deep";
            return bool(f.device->createTexture(t));
        }, "exceeds maxTextureSize3D");
    }
    // With limits that allow it, a width of 2^31 has exactly 32 mips.
    Capabilities huge = f.null->capabilities();
    huge.limits.maxTextureSize2D = UINT32_MAX;
    auto null = createNullDevice(&huge);
    auto wrapper = createValidationDevice(*null);
    std::vector<std::string> errors;
    wrapper->setErrorCallback([&](Severity, const std::string& m) { errors.push_back(m); });
    TextureDesc t;
    t.width = 1u << 31;
    t.mipLevels = 32;
    CHECK(wrapper->createTexture(t));
    CHECK(errors.empty());
    t.mipLevels = 33;
    CHECK_FALSE(wrapper->createTexture(t));
    REQUIRE(errors.size() == 1);
    CHECK(errors[0].find("mipLevels 33 out of range 1..32") != std::string::npos);

    // Ranges whose end wraps around 2^32 or 2^64 are out of range, not small.
    f.expectRejected([&] { return f.device->clearTexture(f.source, 1, 0xFFFFFFFFu, ClearValue{}); },
                     "mip range 1+4294967295 out of range");
    TextureDesc layers;
    layers.dimension = TextureDimension::Texture2DArray;
    layers.depthOrLayers = 4;
    layers.debugName = "layers";
    const TextureHandle array = f.device->createTexture(layers);
    REQUIRE(array);
    std::vector<uint8_t> texel(64);
    f.expectRejected([&] { return f.device->writeTexture(array, {0, 1, 0xFFFFFFFFu}, texel.data()); },
                     "layers 1+4294967295 out of range");
    f.expectRejected([&] { return f.device->copyBuffer(f.counters, 0, f.weights, UINT64_MAX - 3, 8); },
                     "src range: range [18446744073709551612, +8) exceeds buffer 'weights' of 256 bytes");
    f.expectRejected([&] { return f.device->readBuffer(f.weights, 8, UINT64_MAX, texel.data()); }, "exceeds buffer");
    const auto seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    CHECK(seconds < 5.0);
}

TEST_CASE("values outside their enum or capacity are rejected", "[validation]") {
    Fixture f;
    f.expectRejected([&] {
        TextureDesc t;
        t.dimension = TextureDimension(9);
        t.debugName = "odd";
        return bool(f.device->createTexture(t));
    }, "createTexture 'odd': dimension 9 is not a TextureDimension");
    f.expectRejected([&] {
        SamplerDesc s;
        s.addressV = AddressMode(7);
        return bool(f.device->createSampler(s));
    }, "addressV 7 is out of range");
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.bindings.storageBuffers[0].access = Access(5);
        return f.device->dispatch(s, 1, 1, 1);
    }, "storageBuffers[0] (slot 0).access: 5 is out of range (0..3)");
    f.expectRejected([&] {
        DispatchState s = f.good();
        s.bindings.textures.count = 200;  // a public field: loops would read past the 16 entries
        return f.device->dispatch(s, 1, 1, 1);
    }, "textures: count 200 exceeds the capacity 16");
}

TEST_CASE("subresourceBytes is safe for any description", "[validation][cpu]") {
    TextureDesc d;
    d.format = Format::RGBA32_FLOAT;
    d.width = d.height = 4;
    CHECK(subresourceBytes(d, {}) == 4 * 4 * 16);
    CHECK(subresourceBytes(d, {1, 0, 1}) == 0);  // no mip 1
    // 2^31 x 2^31 x 2^31 texels of 16 bytes do not fit 64 bits: 0, never a wrapped-around small count.
    d.dimension = TextureDimension::Texture3D;
    d.width = d.height = d.depthOrLayers = 1u << 31;
    CHECK(subresourceBytes(d, {}) == 0);
    d.dimension = TextureDimension::Texture2DArray;
    d.width = d.height = 1;
    d.depthOrLayers = 8;
    CHECK(subresourceBytes(d, {0, 6, 4}) == 0);  // layers 6..9 of 8
    CHECK(subresourceBytes(d, {0, 6, 0}) == 2 * 16);
}
