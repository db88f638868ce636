// Transfers and diagnostics: buffer writes/copies/clears and partial read-backs, texture copies and
// clears per mip, markers with GPU timestamps.
#include "case_helpers.h"

namespace bricklight::conformance {
using rhi::Format;

static void transfer_buffer_write_copy_clear(CaseContext& ctx) {
    std::vector<uint32_t> init(256);
    for (uint32_t i = 0; i < 256; ++i) init[i] = i;
    rhi::BufferHandle a = ctx.buffer(1024, kStorageUsage, init.data(), "a");
    rhi::BufferHandle b = ctx.buffer(1024, kStorageUsage, nullptr, "b");
    ctx.check(ctx.device.clearBuffer(b, {}, 0xABCDEF01u), "clear whole");
    const uint32_t patch[4] = {1000, 1001, 1002, 1003};
    ctx.check(ctx.device.writeBuffer(a, 64, patch, sizeof(patch)), "writeBuffer");
    ctx.check(ctx.device.copyBuffer(b, 512, a, 0, 256), "copyBuffer");
    ctx.check(ctx.device.clearBuffer(b, {900, 16}, 7), "clear range");
    auto v = ctx.read<uint32_t>(b, 256);
    ctx.check(v[0] == 0xABCDEF01u && v[127] == 0xABCDEF01u, "clear value kept outside the copy");
    ctx.check(v[128] == 0 && v[128 + 15] == 15 && v[128 + 16] == 1000 && v[128 + 19] == 1003 && v[128 + 20] == 20,
              "copied range includes the earlier write");
    ctx.check(v[225] == 7 && v[228] == 7 && v[224] == 0xABCDEF01u && v[229] == 0xABCDEF01u, "cleared range");
    auto part = ctx.read<uint32_t>(b, 4, 512 + 64);
    ctx.check(part[0] == 1000 && part[3] == 1003, "readBuffer at an offset");
    ctx.output("b", bytesOf(v));
}

static void transfer_large_write_then_dispatch(CaseContext& ctx) {
    // 65 537 values: past 64 KiB, where one driver (NVIDIA 580, GL) lost a single large glBufferSubData for the
    // dispatches that followed.
    const uint32_t n = 65537;
    std::vector<uint32_t> values(n);
    for (uint32_t i = 0; i < n; ++i) values[i] = i * 3u + 1u;
    rhi::BufferHandle src = ctx.buffer(n * 4, kStorageUsage, nullptr, "written");
    rhi::BufferHandle dst = ctx.buffer(n * 4, kStorageUsage, nullptr, "doubled");
    ctx.check(ctx.device.writeBuffer(src, 0, values.data(), n * 4), "writeBuffer");
    ctx.check(dispatchChainStep(ctx.device, ctx.shader("rhi_tests/chain_step.comp"), "double", src, dst, n, 5), "dispatch");
    auto v = ctx.read<uint32_t>(dst, n);
    for (uint32_t i = 0; i < n; ++i)
        if (!ctx.check(v[i] == values[i] * 2u + 5u, "value " + std::to_string(i))) break;
    ctx.output("doubled", bytesOf(v));
}

static void readback_without_waiting(CaseContext& ctx) {
    const uint32_t n = 256;
    rhi::BufferHandle out = ctx.buffer(n * 4, kStorageUsage, nullptr, "values");
    struct { uint32_t count, scale, offset; } p{n, 5, 1};
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/fill_buffer.comp");
    s.label = "fill";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
    ctx.check(ctx.device.dispatch(s, groupsFor(n, 64), 1, 1), "dispatch");
    const uint64_t ticket = ctx.device.requestReadback(out, 16, (n - 4) * 4);
    ctx.check(ticket != 0, "requestReadback returns a ticket");
    const uint32_t later[4] = {9, 9, 9, 9};
    ctx.device.writeBuffer(out, 16, later, sizeof(later));  // after the request: must not be seen
    std::vector<uint32_t> v(n - 4, 0);
    rhi::ReadbackStatus status = rhi::ReadbackStatus::Pending;
    // The contract: finished at the latest when endFrame() recycles the frame (a few frames later).
    for (int frame = 0; frame < 8 && status == rhi::ReadbackStatus::Pending; ++frame) {
        ctx.device.endFrame();
        status = ctx.device.pollReadback(ticket, v.data());
    }
    ctx.check(status == rhi::ReadbackStatus::Ready, "Ready within 8 frames");
    for (uint32_t i = 0; i < n - 4; ++i)
        if (!ctx.check(v[i] == (i + 4) * 5 + 1, "value " + std::to_string(i + 4))) break;
    ctx.check(ctx.device.pollReadback(ticket, v.data()) == rhi::ReadbackStatus::Failed, "a taken ticket fails");
    const uint64_t second = ctx.device.requestReadback(out, 0, 16);
    ctx.device.waitIdle();
    uint32_t head[4] = {};
    ctx.check(ctx.device.pollReadback(second, head) == rhi::ReadbackStatus::Ready, "Ready after waitIdle");
    ctx.check(head[0] == 1 && head[3] == 16 && head[2] == 11, "head values");
    ctx.output("values", bytesOf(v));
}

static void new_buffer_reads_zero(CaseContext& ctx) {
    // Several sizes, created after others were destroyed, so that reused memory would show.
    for (uint64_t size : {4ull, 1000ull, 65536ull}) {
        std::vector<uint32_t> junk(size / 4 + 1, 0xDEADBEEFu);
        rhi::BufferHandle old = ctx.buffer(size, kStorageUsage, junk.data(), "junk");
        ctx.device.waitIdle();
        ctx.device.destroy(old);
        rhi::BufferHandle b = ctx.buffer(size, kStorageUsage, nullptr, "fresh");
        std::vector<uint8_t> bytes(size, 0xFF);
        ctx.check(ctx.device.readBuffer(b, 0, size, bytes.data()), "readBuffer");
        bool zero = true;
        for (uint8_t v : bytes) zero &= v == 0;
        ctx.check(zero, "a new buffer of " + std::to_string(size) + " bytes reads as zero");
        if (size == 1000) ctx.output("fresh", bytes);
    }
}

static void transfer_texture_copy_clear(CaseContext& ctx) {
    rhi::TextureDesc d = texture2D(Format::RGBA16_FLOAT, 8, 8, rhi::TextureUsage::Sampled, "src", 2);
    d.dimension = rhi::TextureDimension::Texture2DArray;
    d.depthOrLayers = 2;
    rhi::TextureHandle src = ctx.texture(d);
    d.debugName = "dst";
    rhi::TextureHandle dst = ctx.texture(d);
    rhi::ClearValue half{};
    half.f[0] = 0.5f, half.f[1] = -2.0f, half.f[2] = 4.0f, half.f[3] = 1.0f;
    ctx.check(ctx.device.clearTexture(src, 0, 2, half), "clear all mips");
    ctx.check(ctx.device.clearTexture(dst, 0, 0, rhi::ClearValue{{0, 0, 0, 0}}), "clear dst");
    std::vector<uint16_t> layer(4 * 4 * 4, floatToHalf(3.0f));
    ctx.check(ctx.device.writeTexture(src, {1, 1, 1}, layer.data()), "write mip 1 layer 1");
    ctx.check(ctx.device.copyTexture(dst, {1, 0, 1}, src, {1, 1, 1}), "copy mip 1 layer 1 -> layer 0");
    auto got = ctx.readTexture(dst, {1, 0, 1});
    std::vector<uint16_t> h(got.size() / 2);
    std::memcpy(h.data(), got.data(), got.size());
    ctx.check(halfToFloat(h[0]) == 3.0f && halfToFloat(h[h.size() - 1]) == 3.0f, "copied layer");
    auto untouched = ctx.readTexture(dst, {1, 1, 1});
    std::memcpy(h.data(), untouched.data(), untouched.size());
    ctx.check(halfToFloat(h[0]) == 0.0f, "other layer untouched");
    auto mip0 = ctx.readTexture(src, {0, 0, 0});
    std::vector<uint16_t> m(mip0.size() / 2);
    std::memcpy(m.data(), mip0.data(), mip0.size());
    ctx.check(m.size() == 8 * 8 * 4 * 2 && halfToFloat(m[1]) == -2.0f && halfToFloat(m[m.size() - 2]) == 4.0f,
              "clearTexture float value in both layers of mip 0");
    ctx.output("copied", got);
    ctx.output("mip0", mip0);
}

static void markers_and_timestamps(CaseContext& ctx) {
    const uint32_t n = 65536;
    rhi::BufferHandle out = ctx.buffer(n * 4, kStorageUsage, nullptr, "values");
    rhi::ShaderHandle sh = ctx.shader("rhi_tests/fill_buffer.comp");
    ctx.device.setTimingEnabled(true);
    for (int frame = 0; frame < 2; ++frame) {
        ctx.device.beginMarker("frame");
        for (int pass = 0; pass < 2; ++pass) {
            ctx.device.beginMarker(pass ? "second" : "first");
            struct { uint32_t count, scale, offset; } p{n, uint32_t(pass + 1), uint32_t(frame)};
            rhi::DispatchState s;
            s.shader = sh;
            s.label = "fill";
            s.bindings.constants.push(rhi::constants(0, p));
            s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
            ctx.device.dispatch(s, n / 64, 1, 1);
            ctx.device.endMarker();
        }
        ctx.device.endMarker();
        ctx.device.endFrame();
    }
    ctx.device.waitIdle();
    auto timings = ctx.device.takeTimings();
    ctx.device.setTimingEnabled(false);
    if (!ctx.device.capabilities().timestamps) {
        ctx.check(timings.empty(), "no timestamps reported, so no timings expected");
        return;
    }
    int frames = 0, firsts = 0, seconds = 0;
    bool valid = true;
    for (const auto& t : timings) {
        frames += t.label == "frame";
        firsts += t.label == "frame/first";
        seconds += t.label == "frame/second";
        valid &= t.milliseconds >= 0.0 && t.milliseconds < 10000.0;
    }
    ctx.check(frames == 2 && firsts == 2 && seconds == 2,
              "expected 2 timings each of frame, frame/first, frame/second; got " + std::to_string(timings.size()));
    ctx.check(valid, "timings must be non-negative milliseconds");
    auto again = ctx.device.takeTimings();
    ctx.check(again.empty(), "takeTimings returns each result once");
    auto v = ctx.read<uint32_t>(out, 4);
    ctx.check(v[3] == 3 * 2 + 1, "the timed work ran");
    ctx.output("values", bytesOf(v));
}

void appendTransferCases(std::vector<Case>& out) {
    out.insert(out.end(), {
        BL_CASE(transfer_buffer_write_copy_clear, "writeBuffer at offsets, copyBuffer between buffers, clearBuffer ranges, readBuffer subranges"),
        BL_CASE(transfer_large_write_then_dispatch, "a writeBuffer of 256 KiB is seen in full by the next dispatch"),
        BL_CASE(readback_without_waiting, "requestReadback/pollReadback: sees the writes before it, not after; Ready within the frames in flight; a ticket is taken once"),
        BL_CASE(new_buffer_reads_zero, "createBuffer without initial data: the contents read as zero"),
        BL_CASE(transfer_texture_copy_clear, "copyTexture between mips/layers, clearTexture float per mip, writeTexture of one array layer"),
        BL_CASE(markers_and_timestamps, "beginMarker/endMarker nesting, setTimingEnabled, takeTimings after endFrame/waitIdle"),
    });
}

}  // namespace bricklight::conformance
