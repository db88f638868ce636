// Hazards: the backend places barriers from the declared access alone. Long dependency chains fail if a
// barrier is missed on a GPU that overlaps dispatches; on drivers that serialise everything (lavapipe,
// llvmpipe) the barrier counts and the Vulkan synchronization validation catch what the values cannot.
// Where the backend cannot count its barriers, ctx.barriers() is empty: those checks are skipped, with a note.
#include <optional>

#include "case_helpers.h"

namespace bricklight::conformance {
using rhi::Format;

namespace {
constexpr uint32_t kChainLength = 48;
constexpr uint32_t kElements = 16384;
}  // namespace

static void hazard_read_after_write_chain(CaseContext& ctx) {
    std::vector<uint32_t> init(kElements);
    for (uint32_t i = 0; i < kElements; ++i) init[i] = i & 7;
    rhi::BufferHandle a = ctx.buffer(kElements * 4, kStorageUsage, init.data(), "ping");
    rhi::BufferHandle b = ctx.buffer(kElements * 4, kStorageUsage, nullptr, "pong");
    rhi::ShaderHandle sh = ctx.shader("rhi_tests/chain_step.comp");
    const std::optional<uint64_t> before = ctx.barriers();
    for (uint32_t step = 0; step < kChainLength; ++step) {
        dispatchChainStep(ctx.device, sh, "chain", step % 2 ? b : a, step % 2 ? a : b, kElements, step);
    }
    const std::optional<uint64_t> after = ctx.barriers();
    auto v = ctx.read<uint32_t>(kChainLength % 2 ? b : a, kElements);
    for (uint32_t i = 0; i < kElements; i += 97) {
        uint32_t x = i & 7;
        for (uint32_t step = 0; step < kChainLength; ++step) x = x * 2 + step;
        if (!ctx.check(v[i] == x, "element " + std::to_string(i) + " after the chain")) break;
    }
    // Every link after the first reads what the previous one wrote: at least one barrier each.
    if (before && after)
        ctx.check(*after - *before >= kChainLength - 1,
                  "a read-after-write got no barrier (" + std::to_string(*after - *before) + " barriers for " +
                      std::to_string(kChainLength - 1) + " dependencies)");
    ctx.output("result", bytesOf(v));
}

static void hazard_texture_chain(CaseContext& ctx) {
    const uint32_t n = 32, links = 24;
    rhi::TextureDesc d = texture2D(Format::R32_FLOAT, n, n, rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage, "ping");
    rhi::TextureHandle t[2] = {ctx.texture(d), ctx.texture(d)};
    ctx.device.clearTexture(t[0], 0, 1, rhi::ClearValue{{1.0f, 0, 0, 0}});
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "nearest";
    rhi::SamplerHandle samp = ctx.sampler(sd);
    rhi::ShaderHandle sh = ctx.shader("rhi_tests/image_chain_step.comp");
    for (uint32_t i = 0; i < links; ++i) {
        struct { int32_t w, h; float step; } p{int32_t(n), int32_t(n), float(i + 1)};
        rhi::DispatchState s;
        s.shader = sh;
        s.label = "texture chain";
        s.bindings.constants.push(rhi::constants(0, p));
        s.bindings.textures.push({0, rhi::wholeTexture(t[i % 2]), samp});
        s.bindings.storageImages.push({0, rhi::textureMip(t[(i + 1) % 2], 0), rhi::Access::Write});
        ctx.device.dispatch(s, n / 8, n / 8, 1);
    }
    auto bytes = ctx.readTexture(t[links % 2]);
    float v;
    std::memcpy(&v, bytes.data() + 4 * (5 * n + 9), 4);
    ctx.check(v == 1.0f + links * (links + 1) / 2.0f, "texture chain result " + std::to_string(v));
    ctx.output("result", bytes);
}

static void hazard_write_after_write(CaseContext& ctx) {
    const uint32_t n = 4096;
    rhi::BufferHandle out = ctx.buffer(n * 4, kStorageUsage, nullptr, "target");
    rhi::ShaderHandle sh = ctx.shader("rhi_tests/fill_buffer.comp");
    const std::optional<uint64_t> before = ctx.barriers();
    for (uint32_t i = 0; i < 32; ++i) {
        struct { uint32_t count, scale, offset; } p{n, i, i * 100};
        rhi::DispatchState s;
        s.shader = sh;
        s.label = "overwrite";
        s.bindings.constants.push(rhi::constants(0, p));
        s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
        ctx.device.dispatch(s, n / 64, 1, 1);
    }
    const std::optional<uint64_t> after = ctx.barriers();
    auto v = ctx.read<uint32_t>(out, n);
    ctx.check(v[1234] == 1234 * 31 + 3100 && v[0] == 3100, "the last write must win");
    if (before && after)
        ctx.check(*after - *before >= 31, "a write-after-write got no barrier (" + std::to_string(*after - *before) +
                                              " barriers for 31 dependencies)");
    ctx.output("result", bytesOf(v));
}

static void hazard_write_after_read(CaseContext& ctx) {
    const uint32_t n = 4096;
    std::vector<uint32_t> init(n, 3);
    rhi::BufferHandle src = ctx.buffer(n * 4, kStorageUsage, init.data(), "source");
    rhi::BufferHandle dst = ctx.buffer(n * 4, kStorageUsage, nullptr, "copy");
    dispatchChainStep(ctx.device, ctx.shader("rhi_tests/chain_step.comp"), "read source", src, dst, n, 1);
    struct { uint32_t count, scale, offset; } f{n, 0, 99};
    rhi::DispatchState overwrite;
    overwrite.shader = ctx.shader("rhi_tests/fill_buffer.comp");
    overwrite.label = "overwrite source";
    overwrite.bindings.constants.push(rhi::constants(0, f));
    overwrite.bindings.storageBuffers.push({0, src, {}, rhi::Access::Write});
    ctx.device.dispatch(overwrite, n / 64, 1, 1);
    auto copy = ctx.read<uint32_t>(dst, n);
    auto source = ctx.read<uint32_t>(src, n);
    ctx.check(copy[777] == 7 && source[777] == 99, "the read saw the later write, or the write was lost");
    ctx.output("copy", bytesOf(copy));
}

static void hazard_read_after_read_no_barrier(CaseContext& ctx) {
    const uint32_t n = 1024;
    std::vector<uint32_t> init(n, 2);
    rhi::BufferHandle src = ctx.buffer(n * 4, rhi::BufferUsage::ShaderRead, init.data(), "shared input");
    rhi::BufferHandle sum = ctx.buffer(16, kStorageUsage, nullptr, "sum");
    rhi::ShaderHandle sh = ctx.shader("rhi_tests/sum_buffer.comp");
    rhi::DispatchState s;
    s.shader = sh;
    s.label = "sum";
    s.bindings.constants.push(rhi::constants(0, n));
    s.bindings.readBuffers.push({0, src, {}});
    s.bindings.storageBuffers.push({0, sum, {}, rhi::Access::Atomic});
    ctx.device.dispatch(s, n / 64, 1, 1);
    const std::optional<uint64_t> before = ctx.barriers();
    s.flags = rhi::DispatchFlags::NoBarrierWithPreviousWriter;
    for (int i = 0; i < 4; ++i) ctx.device.dispatch(s, n / 64, 1, 1);
    const std::optional<uint64_t> after = ctx.barriers();
    auto v = ctx.read<uint32_t>(sum, 1);
    ctx.check(v[0] == 5 * 2 * n, "atomic accumulation over 5 dispatches: " + std::to_string(v[0]));
    if (before && after)
        ctx.check(*after == *before, "read-after-read or flagged atomic accumulation placed " +
                                         std::to_string(*after - *before) + " barrier(s)");
    ctx.output("sum", bytesOf(v));
}

void appendHazardCases(std::vector<Case>& out) {
    out.insert(out.end(), {
        BL_CASE(hazard_read_after_write_chain, "read-after-write across 48 dispatches ping-ponging two buffers (readBuffers <- storageBuffers)"),
        BL_CASE(hazard_texture_chain, "read-after-write of textures: storage image written, sampled by the next dispatch, 24 links"),
        BL_CASE(hazard_write_after_write, "write-after-write: 32 dispatches overwrite one buffer; the last one wins"),
        BL_CASE(hazard_write_after_read, "write-after-read: a buffer read by one dispatch and overwritten by the next keeps the read's result"),
        BL_CASE(hazard_read_after_read_no_barrier, "read-after-read places no barrier; NoBarrierWithPreviousWriter lets atomics accumulate across dispatches"),
    });
}

}  // namespace bricklight::conformance
