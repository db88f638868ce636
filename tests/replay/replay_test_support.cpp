#include "replay_test_support.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <sstream>

namespace bricklight::testing {

using namespace rhi;

namespace {
std::vector<uint8_t> pattern(size_t size, uint8_t seed) {
    std::vector<uint8_t> bytes(size);
    for (size_t i = 0; i < size; ++i) bytes[i] = uint8_t(seed + i * 7);
    return bytes;
}
ShaderHandle shader(IDevice& d, const char* name) {
    const ShaderBlob* blob = findShader(name);
    REQUIRE(blob);
    return d.createShader({blob, ""});
}
}  // namespace

void runSession(IDevice& d) {
    const ShaderHandle probe = shader(d, "rhi_tests/validation_probe.comp");
    const ShaderHandle vs = shader(d, "rhi_tests/smoke_vk_triangle.vert");
    const ShaderHandle fs = shader(d, "rhi_tests/smoke_vk_triangle.frag");

    TextureDesc t;
    t.width = t.height = 16;
    t.mipLevels = 2;
    t.format = Format::RGBA8_UNORM;
    t.usage = TextureUsage::Sampled | TextureUsage::Storage;
    t.debugName = "source";
    const std::vector<uint8_t> sourceData = pattern(16 * 16 * 4 + 8 * 8 * 4, 1);
    const TextureHandle source = d.createTexture(t, sourceData.data());
    t.debugName = "copy";
    const TextureHandle copy = d.createTexture(t);
    t.mipLevels = 1;
    t.format = Format::RGBA16_FLOAT;
    t.usage = TextureUsage::Sampled | TextureUsage::Storage | TextureUsage::RenderTarget;
    t.debugName = "target";
    const TextureHandle target = d.createTexture(t);
    t.format = Format::RGBA8_UNORM;
    t.usage = TextureUsage::RenderTarget;
    t.debugName = "colour";
    const TextureHandle colour = d.createTexture(t);

    const std::vector<uint8_t> weightData = pattern(256, 3);
    const BufferHandle weights = d.createBuffer({256, 0, BufferUsage::ShaderRead | BufferUsage::ShaderWrite, "weights"},
                                                weightData.data());
    const BufferHandle counters = d.createBuffer({256, 4, BufferUsage::ShaderRead | BufferUsage::ShaderWrite, "counters"});
    const uint32_t argWords[16] = {2, 2, 1, 0, 3, 1, 0, 0, 3, 1, 0, 0, 0, 0, 0, 0};  // dispatch, draw, indexed draw
    const BufferHandle args = d.createBuffer({sizeof(argWords), 0, BufferUsage::IndirectArgs, "args"}, argWords);
    const float vertices[3][7] = {{-1, -1, 0, 1, 0, 0, 1}, {3, -1, 0, 0, 1, 0, 1}, {-1, 3, 0, 0, 0, 1, 1}};
    const BufferHandle vertexBuffer = d.createBuffer({sizeof(vertices), 0, BufferUsage::Vertex, "vertices"}, vertices);
    const uint32_t indices[3] = {0, 1, 2};
    const BufferHandle indexBuffer = d.createBuffer({sizeof(indices), 0, BufferUsage::Index, "indices"}, indices);
    SamplerDesc sd;
    sd.minFilter = Filter::Nearest;
    sd.maxLod = 8.5f;
    sd.debugName = "nearest";
    const SamplerHandle sampler = d.createSampler(sd);

    const std::vector<uint8_t> update = pattern(40, 9);
    d.writeBuffer(weights, 16, update.data(), update.size());
    const std::vector<uint8_t> mip1 = pattern(8 * 8 * 4, 5);
    d.writeTexture(source, {1, 0, 0}, mip1.data());
    d.copyBuffer(counters, 0, weights, 64, 64);
    d.copyTexture(copy, {0, 0, 0}, source, {0, 0, 0});
    d.clearBuffer(counters, {128, 0}, 7u);
    ClearValue black{};
    black.f[3] = 1.0f;
    d.clearTexture(target, 0, 1, black);
    std::vector<uint8_t> out(16 * 16 * 8);
    d.readBuffer(weights, 0, 64, out.data());
    const uint64_t ticket = d.requestReadback(weights, 0, 16);
    d.readTexture(source, {0, 0, 0}, out.data());

    d.setTimingEnabled(true);
    d.setTimingDepth(2);
    d.beginMarker("frame");
    const float scale[4] = {1, 0.5f, 0.25f, 1};
    DispatchState ds;
    ds.shader = probe;
    ds.label = "probe";
    ds.bindings.constants.push(ConstantsBinding{0, scale, sizeof(scale)});
    ds.bindings.textures.push(TextureBinding{0, wholeTexture(source), sampler});
    ds.bindings.readBuffers.push(ReadBufferBinding{0, weights, {0, 128}});
    ds.bindings.storageBuffers.push(StorageBufferBinding{0, counters, {}, Access::Atomic});
    ds.bindings.storageImages.push(StorageImageBinding{0, textureMip(target, 0), Access::Write});
    d.dispatch(ds, 2, 2, 1);
    ds.flags = DispatchFlags::NoBarrierWithPreviousWriter;
    d.dispatchIndirect(ds, args, 0);

    DrawCallState s;
    s.vertexShader = vs;
    s.fragmentShader = fs;
    s.label = "triangle";
    s.vertexInputs.push(VertexInput{0, VertexFormat::Float3, 0, 0});
    s.vertexInputs.push(VertexInput{1, VertexFormat::Float4, 0, 12});
    s.vertexBuffers.push(VertexBufferBinding{vertexBuffer, 0, sizeof(vertices[0]), false});
    s.indexBuffer = IndexBufferBinding{indexBuffer, 0, IndexFormat::U32};
    ColorTarget ct;
    ct.view = textureMip(colour, 0);
    ct.load = LoadOp::Clear;
    ct.clearColor[0] = 0.25f;
    ct.blend.enable = true;
    ct.blend.srcColor = BlendFactor::SrcAlpha;
    ct.blend.dstColor = BlendFactor::OneMinusSrcAlpha;
    s.colorTargets.push(ct);
    s.raster.cull = CullMode::Back;
    s.raster.depthBiasSlope = 1.5f;
    s.viewport = Viewport{0, 0, 16, 16, 0, 1};
    s.scissor = ScissorRect{-2, 1, 12, 14};
    d.draw(s, DrawArgs{3, 1, 0, 0});
    d.drawIndexed(s, DrawIndexedArgs{3, 1, 0, -1, 0});
    d.drawIndirect(s, args, 16, false);
    d.drawIndirect(s, args, 32, true);
    d.endMarker();
    d.endFrame();
    d.waitIdle();
    std::vector<uint8_t> polled(16);
    d.pollReadback(ticket, polled.data());

    d.destroy(sampler);
    for (ShaderHandle h : {probe, vs, fs}) d.destroy(h);
    for (TextureHandle h : {source, copy, target, colour}) d.destroy(h);
    for (BufferHandle h : {weights, counters, args, vertexBuffer, indexBuffer}) d.destroy(h);
}

std::vector<json> sessionLines() {
    std::unique_ptr<IDevice> null = createNullDevice();
    std::unique_ptr<IDevice> validation = createValidationDevice(*null);
    std::vector<std::string> errors;
    validation->setErrorCallback([&](Severity, const std::string& m) { errors.push_back(m); });
    std::stringstream text;
    std::unique_ptr<IDevice> recorder = createRecordingDevice(*validation, text);
    runSession(*recorder);
    for (const auto& e : errors) UNSCOPED_INFO(e);
    REQUIRE(errors.empty());
    std::vector<json> lines;
    std::string line;
    while (std::getline(text, line)) lines.push_back(json::parse(line));
    return lines;
}

std::string joinLines(const std::vector<json>& lines) {
    std::string text;
    for (const json& j : lines) text += j.dump() + "\n";
    return text;
}

size_t lineOf(const std::vector<json>& lines, const std::string& call) {
    for (size_t i = 0; i < lines.size(); ++i)
        if (lines[i].at("call") == call) return i;
    FAIL("the session has no " << call << " line");
    return 0;
}

ReplayResult replayOn(IDevice& device, const std::string& text, const ReplayOptions& options) {
    ReplayResult r;
    device.setErrorCallback([&r](Severity s, const std::string& m) {
        if (s == Severity::Error) r.deviceErrors.push_back(m);
    });
    std::istringstream in(text);
    const auto start = std::chrono::steady_clock::now();
    try {
        r.ok = replayRecording(in, device, options, &r.stats, &r.error);
    } catch (...) {
        r.threw = true;
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    device.setErrorCallback(nullptr);
    return r;
}

ReplayResult replayText(const std::string& text, bool validate, const ReplayOptions& options) {
    std::unique_ptr<IDevice> null = createNullDevice();
    if (!validate) return replayOn(*null, text, options);
    std::unique_ptr<IDevice> validation = createValidationDevice(*null);
    return replayOn(*validation, text, options);
}

// ---------------------------------------------------------------------------------------------------
// BufferMemoryDevice
// ---------------------------------------------------------------------------------------------------
BufferHandle BufferMemoryDevice::createBuffer(const BufferDesc& desc, const void* data) {
    if (desc.size > (1u << 20)) return {};
    const BufferHandle h = inner_.createBuffer(desc, data);
    if (!h) return h;
    std::vector<uint8_t>& bytes = buffers_[h.id];
    bytes.assign(size_t(desc.size), 0);
    if (data) std::memcpy(bytes.data(), data, bytes.size());
    return h;
}

void BufferMemoryDevice::destroy(BufferHandle h) {
    buffers_.erase(h.id);
    inner_.destroy(h);
}

std::vector<uint8_t>* BufferMemoryDevice::find(BufferHandle b, uint64_t offset, uint64_t size) {
    auto it = buffers_.find(b.id);
    if (it == buffers_.end() || offset > it->second.size() || size > it->second.size() - offset) return nullptr;
    return &it->second;
}

bool BufferMemoryDevice::writeBuffer(BufferHandle b, uint64_t offset, const void* data, uint64_t size) {
    std::vector<uint8_t>* bytes = find(b, offset, size);
    if (!bytes || (!data && size)) return false;
    if (size) std::memcpy(bytes->data() + offset, data, size_t(size));
    return inner_.writeBuffer(b, offset, data, size);
}

bool BufferMemoryDevice::copyBuffer(BufferHandle dst, uint64_t dstOffset, BufferHandle src, uint64_t srcOffset,
                                    uint64_t size) {
    std::vector<uint8_t>* d = find(dst, dstOffset, size);
    std::vector<uint8_t>* s = find(src, srcOffset, size);
    if (!d || !s) return false;
    std::memmove(d->data() + dstOffset, s->data() + srcOffset, size_t(size));
    return inner_.copyBuffer(dst, dstOffset, src, srcOffset, size);
}

bool BufferMemoryDevice::clearBuffer(BufferHandle b, BufferRange range, uint32_t value) {
    auto it = buffers_.find(b.id);
    if (it == buffers_.end() || range.offset > it->second.size()) return false;
    const uint64_t size = range.size ? range.size : it->second.size() - range.offset;
    std::vector<uint8_t>* bytes = find(b, range.offset, size);
    if (!bytes) return false;
    for (uint64_t i = 0; i < size; ++i) (*bytes)[size_t(range.offset + i)] = uint8_t(value >> (i % 4 * 8));
    return inner_.clearBuffer(b, range, value);
}

bool BufferMemoryDevice::readBuffer(BufferHandle b, uint64_t offset, uint64_t size, void* out) {
    const std::vector<uint8_t>* bytes = find(b, offset, size);
    if (!bytes || (!out && size)) return false;
    if (size) std::memcpy(out, bytes->data() + offset, size_t(size));
    return true;
}

const std::vector<uint8_t>* BufferMemoryDevice::contents(BufferHandle b) const {
    auto it = buffers_.find(b.id);
    return it == buffers_.end() ? nullptr : &it->second;
}

}  // namespace bricklight::testing
