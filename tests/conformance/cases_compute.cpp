// Storage buffers and images, atomics on both, and inline constants.
#include <cmath>

#include "case_helpers.h"

namespace bricklight::conformance {
using rhi::Format;

static void storage_buffer_fill(CaseContext& ctx) {
    const uint32_t n = 1000;
    rhi::BufferHandle out = ctx.buffer(n * 4, kStorageUsage, nullptr, "values");
    struct { uint32_t count, scale, offset; } p{n, 3, 7};
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/fill_buffer.comp");
    s.label = "fill";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
    ctx.check(ctx.device.dispatch(s, groupsFor(n, 64), 1, 1), "dispatch");
    auto v = ctx.read<uint32_t>(out, n);
    for (uint32_t i = 0; i < n; ++i)
        if (!ctx.check(v[i] == i * 3 + 7, "value " + std::to_string(i))) break;
    ctx.output("values", bytesOf(v));
}

static void storage_buffer_ranges(CaseContext& ctx) {
    const uint32_t n = 64;
    std::vector<uint32_t> src(n * 4);
    for (uint32_t i = 0; i < src.size(); ++i) src[i] = i;
    // One buffer holding both the source (at 256 bytes) and the destination (at 1024 bytes): the
    // ranges do not overlap, so reading one and writing the other is allowed.
    std::vector<uint32_t> init(1024, 0xFFFFFFFFu);
    std::memcpy(&init[64], src.data(), n * 4);
    rhi::BufferHandle buf = ctx.buffer(init.size() * 4, kStorageUsage, init.data(), "shared");
    struct { uint32_t count, step; } p{n, 5};
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/chain_step.comp");
    s.label = "ranges";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.readBuffers.push({0, buf, {256, n * 4}});
    s.bindings.storageBuffers.push({0, buf, {1024, n * 4}, rhi::Access::Write});
    ctx.check(ctx.device.dispatch(s, 1, 1, 1), "dispatch");
    auto v = ctx.read<uint32_t>(buf, 1024);
    for (uint32_t i = 0; i < n; ++i) ctx.check(v[256 + i] == i * 2 + 5, "dst " + std::to_string(i));
    ctx.check(v[255] == 0xFFFFFFFFu && v[256 + n] == 0xFFFFFFFFu, "write escaped its range");
    ctx.check(v[64] == 0, "source changed");
    ctx.output("buffer", bytesOf(v));
}

static void storage_image_write_rgba8(CaseContext& ctx) {
    rhi::TextureHandle img = ctx.texture(texture2D(Format::RGBA8_UNORM, 20, 12, rhi::TextureUsage::Storage, "image"));
    struct { int32_t w, h; uint32_t seed; } p{20, 12, 3};
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/image_write_rgba8.comp");
    s.label = "write rgba8";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.storageImages.push({0, rhi::textureMip(img, 0), rhi::Access::Write});
    ctx.device.dispatch(s, 3, 2, 1);
    auto bytes = ctx.readTexture(img);
    bool ok = bytes.size() == 20 * 12 * 4;
    for (uint32_t y = 0; ok && y < 12; ++y)
        for (uint32_t x = 0; x < 20; ++x) {
            uint32_t v = x * 7 + y * 13 + 3;
            const uint8_t* t = &bytes[(y * 20 + x) * 4];
            ok &= t[0] == (v & 255) && t[1] == ((v * 3) & 255) && t[2] == x && t[3] == y;
        }
    ctx.check(ok, "rgba8 storage image content (row 0 in memory is y = 0)");
    ctx.output("image", bytes);
}

static void storage_image_read_write(CaseContext& ctx) {
    rhi::TextureHandle img = ctx.texture(texture2D(Format::R32_UINT, 16, 16, rhi::TextureUsage::Storage, "counter image"));
    rhi::ClearValue c{};
    c.u[0] = 2;
    ctx.check(ctx.device.clearTexture(img, 0, 1, c), "clearTexture");
    rhi::ShaderHandle sh = ctx.shader("rhi_tests/image_rmw.comp");
    uint32_t expect = 2;
    for (uint32_t i = 0; i < 4; ++i) {
        struct { int32_t w, h; uint32_t add; } p{16, 16, i + 1};
        rhi::DispatchState s;
        s.shader = sh;
        s.label = "rmw";
        s.bindings.constants.push(rhi::constants(0, p));
        s.bindings.storageImages.push({0, rhi::textureMip(img, 0), rhi::Access::ReadWrite});
        ctx.device.dispatch(s, 2, 2, 1);
        expect = expect * 3 + i + 1;
    }
    auto bytes = ctx.readTexture(img);
    std::vector<uint32_t> v(256);
    std::memcpy(v.data(), bytes.data(), 1024);
    bool ok = true;
    for (uint32_t x : v) ok &= x == expect;
    ctx.check(ok, "after 4 read-write passes every texel is " + std::to_string(expect) + ", got " + std::to_string(v[0]));
    ctx.output("image", bytes);
}

static void atomics_buffer(CaseContext& ctx) {
    const uint32_t n = 4096;
    std::vector<uint32_t> init(5 + 16, 0);
    init[2] = 0xFFFFFFFFu;
    rhi::BufferHandle buf = ctx.buffer(init.size() * 4, kStorageUsage, init.data(), "counters");
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/buffer_atomics.comp");
    s.label = "atomics";
    s.bindings.constants.push(rhi::constants(0, n));
    s.bindings.storageBuffers.push({0, buf, {}, rhi::Access::Atomic});
    ctx.device.dispatch(s, n / 64, 1, 1);
    auto v = ctx.read<uint32_t>(buf, init.size());
    uint32_t xorv = 0;
    for (uint32_t i = 0; i < n; ++i) xorv ^= i;
    ctx.check(v[0] == n * (n - 1) / 2, "atomicAdd sum " + std::to_string(v[0]));
    ctx.check(v[1] == (n - 1) * 7, "atomicMax");
    ctx.check(v[2] == 5, "atomicMin");
    ctx.check(v[3] == xorv, "atomicXor");
    ctx.check(v[4] == 1, "atomicCompSwap");
    for (int b = 0; b < 16; ++b) ctx.check(v[5 + b] == n / 16, "bin " + std::to_string(b));
    ctx.output("counters", bytesOf(v));
}

static void atomics_image(CaseContext& ctx) {
    const uint32_t n = 2048, bins = 8;
    rhi::TextureHandle img = ctx.texture(texture2D(Format::R32_UINT, bins, 4, rhi::TextureUsage::Storage, "bins"));
    std::vector<uint32_t> init(bins * 4, 0);
    for (uint32_t b = 0; b < bins; ++b) init[2 * bins + b] = 0xFFFFFFFFu;
    ctx.device.writeTexture(img, {}, init.data());
    struct { uint32_t count, bins; } p{n, bins};
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/image_atomic.comp");
    s.label = "image atomics";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.storageImages.push({0, rhi::textureMip(img, 0), rhi::Access::Atomic});
    ctx.device.dispatch(s, n / 64, 1, 1);
    auto bytes = ctx.readTexture(img);
    std::vector<uint32_t> v(bins * 4);
    std::memcpy(v.data(), bytes.data(), bytes.size());
    for (uint32_t b = 0; b < bins; ++b) {
        uint32_t sum = 0, mx = 0, mn = ~0u, orv = 0;
        for (uint32_t i = b; i < n; i += bins) sum += i % 4 + 1, mx = std::max(mx, i), mn = std::min(mn, i), orv |= 1u << (i % 32);
        ctx.check(v[b] == sum && v[bins + b] == mx && v[2 * bins + b] == mn && v[3 * bins + b] == orv,
                  "bin " + std::to_string(b));
    }
    ctx.output("bins", bytes);
}

static void constants_std140_two_blocks(CaseContext& ctx) {
    // std140: a vec3 + float share 16 bytes; uvec2 at 16; int at 24; float e[3] has a 16-byte stride at 32;
    // mat4 at 80.
    struct First {
        float a[3];
        float b;
        uint32_t c[2];
        int32_t d;
        float pad0;
        float e[3][4];
        float m[16];
    } first{};
    static_assert(sizeof(First) == 144);
    first.a[0] = 1.5f, first.a[1] = -2.0f, first.a[2] = 3.25f, first.b = 4.0f;
    first.c[0] = 7, first.c[1] = 9, first.d = -11;
    first.e[0][0] = 0.5f, first.e[1][0] = 0.25f, first.e[2][0] = 0.125f;
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) first.m[col * 4 + row] = float(col * 10 + row);
    struct Second {
        float scale[4];
        uint32_t tag;
        uint32_t pad[3];
    } second{{1, 2, 3, 4}, 42, {}};
    rhi::BufferHandle out = ctx.buffer(16 * 4, kStorageUsage, nullptr, "out");
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/constants_layout.comp");
    s.label = "constants";
    s.bindings.constants.push(rhi::constants(0, first));
    s.bindings.constants.push(rhi::constants(1, second));
    s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
    ctx.device.dispatch(s, 1, 1, 1);
    auto v = ctx.read<float>(out, 15);
    float mv[4] = {};
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) mv[row] += first.m[col * 4 + row] * second.scale[col];
    const float expect[15] = {1.5f, -2.0f, 3.25f, 4.0f, 7, 9, -11, 0.5f, 0.25f, 0.125f, mv[0], mv[1], mv[2], mv[3], 42};
    for (int i = 0; i < 15; ++i) ctx.check(v[i] == expect[i], "constant value " + std::to_string(i));
    ctx.output("values", bytesOf(v));
}

static void constants_copied_at_call_time(CaseContext& ctx) {
    const uint32_t n = 64, calls = 24;
    rhi::BufferHandle out = ctx.buffer(n * 4 * calls, kStorageUsage, nullptr, "out");
    rhi::ShaderHandle sh = ctx.shader("rhi_tests/fill_buffer.comp");
    struct { uint32_t count, scale, offset; } p{n, 0, 0};
    for (uint32_t c = 0; c < calls; ++c) {
        p.scale = c + 1;
        p.offset = c * 1000;
        rhi::DispatchState s;
        s.shader = sh;
        s.label = "fill slice";
        s.bindings.constants.push(rhi::constants(0, p));  // points at p, which changes on the next iteration
        s.bindings.storageBuffers.push({0, out, {uint64_t(c) * n * 4, n * 4}, rhi::Access::Write});
        ctx.device.dispatch(s, 1, 1, 1);
    }
    auto v = ctx.read<uint32_t>(out, n * calls);
    for (uint32_t c = 0; c < calls; ++c)
        ctx.check(v[c * n + 5] == 5 * (c + 1) + c * 1000, "call " + std::to_string(c) + " saw another call's constants");
    ctx.output("values", bytesOf(v));
}

void appendComputeCases(std::vector<Case>& out) {
    out.insert(out.end(), {
        BL_CASE(storage_buffer_fill, "storageBuffers (write), constants, dispatch group counts"),
        BL_CASE(storage_buffer_ranges, "BufferRange offset/size on read and storage buffers (views into one buffer)"),
        BL_CASE(storage_image_write_rgba8, "storageImages (write) of an RGBA8 2D image, readTexture"),
        BL_CASE(storage_image_read_write, "storageImages (read-write) load-modify-store on R32_UINT, clearTexture uint"),
        BL_CASE(atomics_buffer, "storageBuffers with Access::Atomic: add, max, min, xor, compare-swap"),
        BL_CASE(atomics_image, "storageImages with Access::Atomic on R32_UINT: add, max, min, or"),
        BL_CASE(constants_std140_two_blocks, "constants: two blocks in one record, std140 padding (vec3+float, scalar arrays, mat4)"),
        BL_CASE(constants_copied_at_call_time, "constants: the bytes are copied when the call is made (the caller's memory may change after)"),
    });
}

}  // namespace bricklight::conformance
