// Texture views inline in the binding: mip ranges, array layers, 3D textures and cubes.
#include <cmath>

#include "case_helpers.h"

namespace bricklight::conformance {
namespace {
using rhi::Format;

rhi::SamplerHandle nearestSampler(CaseContext& ctx) {
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "nearest";
    return ctx.sampler(sd);
}

// texelFetch of every texel of lod 0 of a 4 × 4 view (rhi_tests/fetch_float.comp) into `out`: 16 vec4s, row-major.
std::vector<float> fetch4x4(CaseContext& ctx, const rhi::TextureView& view, rhi::BufferHandle out, const char* label) {
    struct { int32_t w, h, lod; } p{4, 4, 0};
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/fetch_float.comp");
    s.label = label;
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.textures.push({0, view, nearestSampler(ctx)});
    s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
    ctx.device.dispatch(s, 1, 1, 1);
    return ctx.read<float>(out, 16 * 4);
}

// Fills texel (x, y) of mip m / layer l with a value that names it: x + 16 y + 256 m + 4096 l.
float texelName(uint32_t x, uint32_t y, uint32_t mip, uint32_t layer) {
    return float(x + 16 * y + 256 * mip + 4096 * layer);
}
}  // namespace

static void view_mip_range(CaseContext& ctx) {
    rhi::TextureDesc d = texture2D(Format::R32_FLOAT, 8, 8, rhi::TextureUsage::Sampled, "mipped", 4);
    std::vector<float> init;
    for (uint32_t m = 0; m < 4; ++m)
        for (uint32_t y = 0; y < (8u >> m); ++y)
            for (uint32_t x = 0; x < (8u >> m); ++x) init.push_back(texelName(x, y, m, 0));
    rhi::TextureHandle tex = ctx.texture(d, init.data());
    for (uint32_t m = 0; m < 4; ++m) {
        auto bytes = ctx.readTexture(tex, {m, 0, 0});
        ctx.check(bytes.size() == size_t(8u >> m) * (8u >> m) * 4, "mip size");
        float first;
        std::memcpy(&first, bytes.data(), 4);
        ctx.check(first == texelName(0, 0, m, 0), "readTexture mip " + std::to_string(m) + " returned another mip");
    }
    rhi::ShaderHandle sh = ctx.shader("rhi_tests/fetch_float.comp");
    rhi::BufferHandle out = ctx.buffer(4 * 4 * 16, kStorageUsage, nullptr, "out");
    // View of mips 1..2: lod 0 of the view is mip 1 of the texture.
    rhi::TextureView view{tex};
    view.baseMip = 1;
    view.mipCount = 2;
    struct { int32_t w, h, lod; } p{4, 4, 0};
    rhi::DispatchState s;
    s.shader = sh;
    s.label = "fetch mip view";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.textures.push({0, view, nearestSampler(ctx)});
    s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
    ctx.device.dispatch(s, 1, 1, 1);
    auto got = ctx.read<float>(out, 16 * 4);
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x)
            ctx.check(got[(y * 4 + x) * 4] == texelName(x, y, 1, 0), "view lod 0 is not mip 1 at " + std::to_string(x) +
                                                                         "," + std::to_string(y));
    // lod 1 of the same view is mip 2.
    p = {2, 2, 1};
    s.bindings.constants[0] = rhi::constants(0, p);
    ctx.device.dispatch(s, 1, 1, 1);
    got = ctx.read<float>(out, 4 * 4);
    ctx.check(got[0] == texelName(0, 0, 2, 0) && got[4] == texelName(1, 0, 2, 0), "view lod 1 is not mip 2");
    ctx.output("mip2", bytesOf(got));
}

static void view_array_layers(CaseContext& ctx) {
    rhi::TextureDesc d = texture2D(Format::R32_FLOAT, 4, 4, rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage, "layers");
    d.dimension = rhi::TextureDimension::Texture2DArray;
    d.depthOrLayers = 4;
    rhi::TextureHandle tex = ctx.texture(d);
    // Write all layers with a layered storage image binding.
    struct { int32_t w, h, layers, pad; float offset; } wp{4, 4, 4, 0, 0.5f};
    rhi::DispatchState w;
    w.shader = ctx.shader("rhi_tests/image_write_r32f.comp");
    w.label = "write layers";
    w.bindings.constants.push(rhi::constants(0, wp));
    w.bindings.storageImages.push({0, rhi::textureMip(tex, 0), rhi::Access::Write});
    ctx.device.dispatch(w, 1, 1, 4);
    for (uint32_t l = 0; l < 4; ++l) {
        auto bytes = ctx.readTexture(tex, {0, l, 1});
        float v;
        std::memcpy(&v, bytes.data() + (1 * 4 + 2) * 4, 4);  // x 2, y 1
        ctx.check(v == 2.0f + 1000.0f + 1e6f * l + 0.5f, "layer " + std::to_string(l) + " not written");
    }
    // Sample layers 1..2 through a 2D array view: view layer 0 is texture layer 1.
    rhi::TextureView view{tex};
    view.baseLayer = 1;
    view.layerCount = 2;
    rhi::BufferHandle out = ctx.buffer(4 * 4 * 2 * 16, kStorageUsage, nullptr, "out");
    struct { int32_t w, h, layers, pad; } sp{4, 4, 2, 0};
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/sample_array.comp");
    s.label = "fetch layers";
    s.bindings.constants.push(rhi::constants(0, sp));
    s.bindings.textures.push({0, view, nearestSampler(ctx)});
    s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
    ctx.device.dispatch(s, 1, 1, 2);
    auto got = ctx.read<float>(out, 32 * 4);
    ctx.check(got[0] == 1e6f + 0.5f, "array view layer 0 should be texture layer 1");
    ctx.check(got[16 * 4 + 5 * 4] == 1.0f + 1000.0f + 2e6f + 0.5f, "array view layer 1 should be texture layer 2");
    ctx.output("layers", bytesOf(got));
    // A single layer viewed as a plain 2D texture.
    rhi::TextureView one{tex};
    one.baseLayer = 3;
    one.layerCount = 1;
    got = fetch4x4(ctx, one, out, "fetch one layer");
    ctx.check(got[(3 * 4 + 3) * 4] == 3.0f + 3000.0f + 3e6f + 0.5f, "2D view of layer 3 returned another layer");
}

static void view_3d_storage_and_sampled(CaseContext& ctx) {
    rhi::TextureDesc d;
    d.dimension = rhi::TextureDimension::Texture3D;
    d.format = Format::R32_UINT;
    d.width = 8;
    d.height = 4;
    d.depthOrLayers = 8;
    d.mipLevels = 2;
    d.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage;
    d.debugName = "volume";
    rhi::TextureHandle tex = ctx.texture(d);
    rhi::ShaderHandle write = ctx.shader("rhi_tests/image_write_3d.comp");
    for (uint32_t m = 0; m < 2; ++m) {
        struct { int32_t w, h, d, add; } p{int32_t(8 >> m), int32_t(4 >> m), int32_t(8 >> m), int32_t(m * 7)};
        rhi::DispatchState s;
        s.shader = write;
        s.label = "write volume mip";
        s.bindings.constants.push(rhi::constants(0, p));
        s.bindings.storageImages.push({0, rhi::textureMip(tex, uint8_t(m)), rhi::Access::Write});
        ctx.device.dispatch(s, 2, 1, 2);
    }
    for (uint32_t m = 0; m < 2; ++m) {
        auto bytes = ctx.readTexture(tex, {m, 0, 0});
        uint32_t w = 8 >> m, h = 4 >> m, dd = 8 >> m;
        ctx.check(bytes.size() == size_t(w) * h * dd * 4, "3D readback covers all slices");
        std::vector<uint32_t> v(bytes.size() / 4);
        std::memcpy(v.data(), bytes.data(), bytes.size());
        bool ok = true;
        for (uint32_t z = 0; z < dd; ++z)
            for (uint32_t y = 0; y < h; ++y)
                for (uint32_t x = 0; x < w; ++x)
                    ok &= v[(z * h + y) * w + x] == x + 100 * y + 10000 * z + m * 7;
        ctx.check(ok, "3D mip " + std::to_string(m) + " content");
        ctx.output("mip" + std::to_string(m), bytes);
    }
}

static void view_cube_faces(CaseContext& ctx) {
    rhi::TextureDesc d = texture2D(Format::RGBA8_UNORM, 4, 4, rhi::TextureUsage::Sampled, "cube");
    d.dimension = rhi::TextureDimension::TextureCube;
    d.depthOrLayers = 6;
    std::vector<uint8_t> init;
    for (uint32_t face = 0; face < 6; ++face)
        for (int t = 0; t < 16; ++t) init.insert(init.end(), {uint8_t(40 * face + 10), uint8_t(face), 0, 255});
    rhi::TextureHandle tex = ctx.texture(d, init.data());
    const float dirs[6][4] = {{1, 0, 0, 0}, {-1, 0, 0, 0}, {0, 1, 0, 0}, {0, -1, 0, 0}, {0, 0, 1, 0}, {0, 0, -1, 0}};
    rhi::BufferHandle dirBuf = ctx.buffer(sizeof(dirs), rhi::BufferUsage::ShaderRead, dirs, "directions");
    rhi::BufferHandle out = ctx.buffer(6 * 16, kStorageUsage, nullptr, "out");
    rhi::SamplerDesc sd;
    sd.debugName = "linear";
    uint32_t count = 6;
    rhi::DispatchState s;
    s.shader = ctx.shader("rhi_tests/sample_cube.comp");
    s.label = "sample cube";
    s.bindings.constants.push(rhi::constants(0, count));
    s.bindings.textures.push({0, rhi::wholeTexture(tex), ctx.sampler(sd)});
    s.bindings.readBuffers.push({0, dirBuf, {}});
    s.bindings.storageBuffers.push({0, out, {}, rhi::Access::Write});
    ctx.device.dispatch(s, 1, 1, 1);
    auto got = ctx.read<float>(out, 24);
    for (uint32_t face = 0; face < 6; ++face)
        ctx.check(std::fabs(got[face * 4] * 255.0f - float(40 * face + 10)) < 0.01f &&
                      std::fabs(got[face * 4 + 1] * 255.0f - float(face)) < 0.01f,
                  "cube face " + std::to_string(face) + " sampled wrong value " + std::to_string(got[face * 4] * 255));
    ctx.output("faces", bytesOf(got), {Tolerance::Kind::Float32, 1e-5});
}

// The packed floats (R11G11B10_FLOAT, RGB9E5_FLOAT) are never storage-capable: a shader writes their bits into an
// R32_UINT texture, and samplers read them through a view in the packed format (the clip-map's traced radiance
// does this with RGB9E5).
static void packedFloatView(CaseContext& ctx, Format format, std::vector<uint32_t> init, void (*decode)(uint32_t, float[3])) {
    while (init.size() < 16) init.push_back(uint32_t(init.size()) * 0x0813A2C5u & 0xF7BDEFBDu);  // no exponent of 31
    rhi::TextureDesc d = texture2D(Format::R32_UINT, 4, 4, rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage, "packed radiance");
    rhi::TextureHandle tex = ctx.texture(d, init.data());
    rhi::TextureView view{tex};
    view.format = format;
    const std::vector<float> got = fetch4x4(ctx, view, ctx.buffer(4 * 4 * 16, kStorageUsage, nullptr, "out"), "fetch packed float view");
    for (uint32_t i = 0; i < 16; ++i) {
        float want[3];
        decode(init[i], want);
        for (int c = 0; c < 3; ++c)
            ctx.check(got[i * 4 + c] == want[c], std::string(rhi::formatName(format)) + " texel " + std::to_string(i) + " channel " +
                                                     std::to_string(c) + " read " + std::to_string(got[i * 4 + c]) + ", its bits say " +
                                                     std::to_string(want[c]));
    }
    ctx.check(got[0] == 1.0f && got[1] == 0.5f && got[2] == 2.0f, std::string(rhi::formatName(format)) + " view does not decode (1, 0.5, 2)");
    ctx.output(rhi::formatName(format), bytesOf(got));
}

static void view_packed_float_of_uint(CaseContext& ctx) {
    // (1, 0.5, 2), (0.25, 4, 0.125), denormals, zero, the largest values, then a spread of words.
    packedFloatView(ctx, Format::R11G11B10_FLOAT,
                    {0x3C0u | (0x380u << 11) | (0x200u << 22), 0x340u | (0x440u << 11) | (0x180u << 22),
                     0x001u | (0x03Fu << 11) | (0x01Fu << 22), 0u, 0x7BFu | (0x7BFu << 11) | (0x3DFu << 22)},
                    decodeR11G11B10);
    // Exponent 17 (× 2^-7): 128, 64, 256 → (1, 0.5, 2); then 0.25, 4, 0.125 at exponent 18 (× 2^-6); small values
    // at exponent 0; zero; the largest.
    packedFloatView(ctx, Format::RGB9E5_FLOAT,
                    {128u | (64u << 9) | (256u << 18) | (17u << 27), 16u | (256u << 9) | (8u << 18) | (18u << 27),
                     1u | (2u << 9) | (511u << 18), 0u, 511u | (511u << 9) | (511u << 18) | (31u << 27)},
                    decodeRgb9e5);
}

void appendViewCases(std::vector<Case>& out) {
    out.insert(out.end(), {
        BL_CASE(view_mip_range, "TextureView.baseMip/mipCount on a sampled 2D texture; readTexture of each mip"),
        BL_CASE(view_array_layers, "2D array textures: layer views (2D of one layer, 2D array of a range), layered storage writes"),
        BL_CASE(view_3d_storage_and_sampled, "3D textures: storage image of one mip (all slices), texelFetch of a 3D mip, readTexture of all slices"),
        BL_CASE(view_cube_faces, "cube textures: initial data per face, samplerCube along the six axes"),
        BL_CASE(view_packed_float_of_uint, "R11G11B10_FLOAT and RGB9E5_FLOAT views of an R32_UINT texture decode the bits written into it"),
    });
}

}  // namespace bricklight::conformance
