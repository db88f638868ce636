// The validation wrapper's checks that every backend needs and that lived in one backend before (issue 35): a
// direct draw's vertices and instances and an indexed draw's indices inside their buffers, usage bits the RHI
// does not define, ids a device hands out twice, and markers nested past kMaxMarkerDepth. On the null device,
// which checks nothing itself: whatever is refused here is refused by the wrapper on every backend.
#include <catch2/catch.hpp>

#include <sstream>

#include "bricklight/rhi_validation.h"
#include "../replay/forwarding_test_device.h"

using namespace bricklight::rhi;

namespace {

struct DrawFixture {
    std::unique_ptr<IDevice> null = createNullDevice();
    std::stringstream forwarded;
    std::unique_ptr<IDevice> recorder = createRecordingDevice(*null, forwarded);
    std::unique_ptr<IDevice> device = createValidationDevice(*recorder);
    std::vector<std::string> errors, warnings;
    TextureHandle target;
    BufferHandle vertices, instances, indices;
    ShaderHandle vs, fs;

    DrawFixture() {
        device->setErrorCallback([this](Severity s, const std::string& m) { (s == Severity::Error ? errors : warnings).push_back(m); });
        TextureDesc t;
        t.width = t.height = 8;
        t.usage = TextureUsage::RenderTarget;
        t.debugName = "target";
        target = device->createTexture(t);
        BufferDesc b;
        b.usage = BufferUsage::Vertex;
        b.size = 3 * 8;  // three vec2 positions
        b.debugName = "positions";
        vertices = device->createBuffer(b);
        b.size = 2 * 24;  // two instances of a vec2 offset and a vec4 colour
        b.debugName = "per-instance";
        instances = device->createBuffer(b);
        b.usage = BufferUsage::Index;
        b.size = 3 * 4;
        b.debugName = "indices";
        indices = device->createBuffer(b);
        vs = device->createShader({findShader("rhi_tests/draw_instanced.vert"), ""});
        fs = device->createShader({findShader("rhi_tests/draw_color.frag"), ""});
        REQUIRE(errors.empty());
    }

    DrawCallState state() const {
        DrawCallState s;
        s.vertexShader = vs;
        s.fragmentShader = fs;
        s.label = "instanced";
        s.vertexBuffers.push(VertexBufferBinding{vertices, 0, 8, false});
        s.vertexBuffers.push(VertexBufferBinding{instances, 0, 24, true});
        s.vertexInputs.push(VertexInput{0, VertexFormat::Float2, 0, 0});
        s.vertexInputs.push(VertexInput{1, VertexFormat::Float2, 1, 0});
        s.vertexInputs.push(VertexInput{2, VertexFormat::Float4, 1, 8});
        s.indexBuffer = IndexBufferBinding{indices, 0, IndexFormat::U32};
        ColorTarget c;
        c.view = textureMip(target, 0);
        s.colorTargets.push(c);
        return s;
    }

    size_t forwardedLines() const {
        const std::string all = forwarded.str();
        return size_t(std::count(all.begin(), all.end(), '\n'));
    }

    // The call fails with one error naming `needle`, and nothing reaches the inner device.
    template <typename F>
    void expectRejected(F&& call, const std::string& needle) {
        errors.clear();
        const size_t before = forwardedLines();
        CHECK_FALSE(call());
        for (const std::string& e : errors) UNSCOPED_INFO("error: " << e);
        REQUIRE(errors.size() == 1);
        INFO("message: " << errors.front());
        CHECK(errors.front().find(needle) != std::string::npos);
        CHECK(forwardedLines() == before);
        errors.clear();
    }
};

// Hands out the id it was told to: a broken engine RHI under the validation wrapper.
class RepeatingIdDevice : public bricklight::testing::ForwardingTestDevice {
public:
    using ForwardingTestDevice::ForwardingTestDevice;
    BufferHandle createBuffer(const BufferDesc& d, const void* data) override {
        ForwardingTestDevice::createBuffer(d, data);
        return BufferHandle{7};
    }
};

}  // namespace

TEST_CASE("draws: the vertices, instances and indices read lie inside their buffers", "[validation]") {
    DrawFixture f;
    CHECK(f.device->draw(f.state(), DrawArgs{3, 2, 0, 0}));
    CHECK(f.device->drawIndexed(f.state(), DrawIndexedArgs{3, 2, 0, 0, 0}));
    CHECK(f.errors.empty());
    f.expectRejected([&] { return f.device->draw(f.state(), DrawArgs{96, 1, 4294967200u, 0}); },
                     "draw 'instanced' (shaders 'rhi_tests/draw_instanced.vert', 'rhi_tests/draw_color.frag'): vertices 4294967200..4294967295 "
                     "read past the end of vertexBuffers[0] buffer 'positions' (24 bytes; location 0 reads up to byte 34359738368)");
    f.expectRejected([&] { return f.device->draw(f.state(), DrawArgs{4, 1, 0, 0}); }, "vertices 0..3 read past the end of vertexBuffers[0]");
    f.expectRejected([&] { return f.device->draw(f.state(), DrawArgs{4294967295u, 1, 0, 0}); }, "vertices 0..4294967294 read past the end");
    f.expectRejected([&] { return f.device->draw(f.state(), DrawArgs{3, 4294967295u, 0, 0}); }, "instances 0..4294967294 read past the end of vertexBuffers[1]");
    f.expectRejected([&] { return f.device->draw(f.state(), DrawArgs{3, 1, 0, 2}); }, "instances 2..2 read past the end of vertexBuffers[1] buffer 'per-instance'");
    f.expectRejected([&] { return f.device->drawIndexed(f.state(), DrawIndexedArgs{3, 1, 1, 0, 0}); },
                     "indices 1..3 read past the end of indexBuffer buffer 'indices' (12 bytes)");
    f.expectRejected([&] { return f.device->drawIndexed(f.state(), DrawIndexedArgs{3, 3, 0, 0, 0}); }, "instances 0..2 read past the end");
    // A stride of 2^32 - 1 and the last vertex index: the furthest byte there is, 2^64 - 2^33 + 9, computed without
    // wrapping.
    DrawCallState wide = f.state();
    wide.vertexBuffers[0].stride = 4294967295u;
    f.expectRejected([&] { return f.device->draw(wide, DrawArgs{1, 1, 4294967295u, 0}); }, "location 0 reads up to byte 18446744065119617033");
    // Zero vertices read nothing: accepted wherever they start.
    CHECK(f.device->draw(f.state(), DrawArgs{0, 1, 4294967295u, 0}));
    CHECK(f.errors.empty());
}

TEST_CASE("usage bits the RHI does not define are refused", "[validation]") {
    DrawFixture f;
    BufferDesc b;
    b.size = 16;
    b.usage = 4294967295u;
    b.debugName = "everything";
    f.expectRejected([&] { return bool(f.device->createBuffer(b)); }, "createBuffer 'everything': usage has unknown bits 0xffffffe0");
    TextureDesc t;
    t.usage = TextureUsage::Sampled | (1u << 9);
    t.debugName = "odd";
    f.expectRejected([&] { return bool(f.device->createTexture(t)); }, "createTexture 'odd': usage has unknown bits 0x200");
}

TEST_CASE("a device that hands out a live id twice is reported", "[validation]") {
    auto null = createNullDevice();
    RepeatingIdDevice repeating(*null);
    auto device = createValidationDevice(repeating);
    std::vector<std::string> errors;
    device->setErrorCallback([&](Severity s, const std::string& m) {
        if (s == Severity::Error) errors.push_back(m);
    });
    BufferDesc b;
    b.size = 16;
    b.debugName = "first";
    CHECK(device->createBuffer(b).id == 7);
    CHECK(errors.empty());
    b.debugName = "second";
    CHECK(device->createBuffer(b).id == 7);
    REQUIRE(errors.size() == 1);
    CHECK(errors[0] == "createBuffer 'second': the device returned buffer handle #7, which is already live (created earlier and not destroyed)");
}

TEST_CASE("markers nest at most kMaxMarkerDepth deep; a deeper one and its end are refused", "[validation]") {
    DrawFixture f;
    const size_t before = f.forwardedLines();
    for (uint32_t i = 0; i < kMaxMarkerDepth; ++i) f.device->beginMarker("level");
    CHECK(f.errors.empty());
    for (int i = 0; i < 3; ++i) f.device->beginMarker("too deep");
    REQUIRE(f.errors.size() == 1);  // one message, not one per refused marker
    CHECK(f.errors[0] == "beginMarker 'too deep': 33 markers open, more than kMaxMarkerDepth 32 (an endMarker missing?); refused");
    CHECK(f.forwardedLines() == before + kMaxMarkerDepth);
    // The ends of the refused ones are not forwarded; the rest close what was opened, and nothing is left.
    for (uint32_t i = 0; i < kMaxMarkerDepth + 3; ++i) f.device->endMarker();
    CHECK(f.forwardedLines() == before + 2 * kMaxMarkerDepth);
    CHECK(f.errors.size() == 1);
    f.device->endMarker();
    REQUIRE(f.errors.size() == 2);
    CHECK(f.errors[1] == "endMarker: no marker is open");
    // 100,000 open markers (a hostile recording) cost a counter, not memory.
    for (int i = 0; i < 100000; ++i) f.device->beginMarker("deep");
    CHECK(f.forwardedLines() == before + 3 * kMaxMarkerDepth);
}
