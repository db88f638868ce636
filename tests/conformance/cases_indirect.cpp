// Indirect dispatch and draw with arguments written by a previous dispatch.
#include "case_helpers.h"

namespace bricklight::conformance {
using rhi::Format;

static void indirect_dispatch_from_gpu_args(CaseContext& ctx) {
    rhi::BufferHandle args = ctx.buffer(64, kStorageUsage | rhi::BufferUsage::IndirectArgs, nullptr, "args");
    struct { uint32_t x, y, z, offset; } p{3, 2, 5, 4};
    rhi::DispatchState w;
    w.shader = ctx.shader("rhi_tests/write_dispatch_args.comp");
    w.label = "write args";
    w.bindings.constants.push(rhi::constants(0, p));
    w.bindings.storageBuffers.push({0, args, {}, rhi::Access::Write});
    ctx.device.dispatch(w, 1, 1, 1);
    rhi::BufferHandle result = ctx.buffer(4 * (4 + 64), kStorageUsage, nullptr, "result");
    ctx.device.clearBuffer(result, {}, 0);
    rhi::DispatchState c;
    c.shader = ctx.shader("rhi_tests/count_groups.comp");
    c.label = "counted";
    c.bindings.storageBuffers.push({0, result, {}, rhi::Access::ReadWrite});
    ctx.check(ctx.device.dispatchIndirect(c, args, 16), "dispatchIndirect");
    auto v = ctx.read<uint32_t>(result, 4 + 30);
    ctx.check(v[0] == 3 * 2 * 5 * 8, "invocations " + std::to_string(v[0]));
    ctx.check(v[1] == 3 && v[2] == 2 && v[3] == 5, "gl_NumWorkGroups");
    bool marks = true;
    for (uint32_t g = 0; g < 30; ++g) marks &= v[4 + g] == g + 1;
    ctx.check(marks, "every group ran once");
    ctx.output("result", bytesOf(v));
}

namespace {
// A 16x16 RGBA8 target cleared to black, and a quad of two triangles (6 vertices, or 4 + 6 indices).
struct QuadScene {
    rhi::TextureHandle target;
    rhi::BufferHandle vertices, indices;
    rhi::DrawCallState state;

    explicit QuadScene(CaseContext& ctx) {
        target = ctx.texture(texture2D(Format::RGBA8_UNORM, 16, 16, rhi::TextureUsage::RenderTarget, "target"));
        // x, y, z, r, g, b, a: a quad over the left half of the target.
        const float v[4][7] = {{-1, -1, 0.5f, 1, 0, 0, 1}, {0, -1, 0.5f, 1, 0, 0, 1}, {-1, 1, 0.5f, 1, 0, 0, 1},
                               {0, 1, 0.5f, 1, 0, 0, 1}};
        vertices = ctx.buffer(sizeof(v), rhi::BufferUsage::Vertex, v, "quad vertices");
        const uint32_t idx[6] = {0, 1, 2, 2, 1, 3};
        indices = ctx.buffer(sizeof(idx), rhi::BufferUsage::Index, idx, "quad indices");
        state.vertexShader = ctx.shader("rhi_tests/draw_color.vert");
        state.fragmentShader = ctx.shader("rhi_tests/draw_color.frag");
        state.vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
        state.vertexInputs.push({1, rhi::VertexFormat::Float4, 0, 12});
        state.vertexBuffers.push({vertices, 0, 28, false});
        state.indexBuffer = {indices, 0, rhi::IndexFormat::U32};
        rhi::ColorTarget ct;
        ct.view = rhi::textureMip(target, 0);
        ct.load = rhi::LoadOp::Clear;
        state.colorTargets.push(ct);
        state.label = "quad";
    }
    // Red pixels in the left half only.
    bool leftHalfRed(CaseContext& ctx, std::vector<uint8_t>* image) {
        *image = ctx.readTexture(target);
        bool ok = image->size() == 16 * 16 * 4;
        for (uint32_t y = 0; ok && y < 16; ++y)
            for (uint32_t x = 0; x < 16; ++x) ok &= (*image)[(y * 16 + x) * 4] == (x < 8 ? 255 : 0);
        return ok;
    }
};
}  // namespace

static void indirect_draw_from_gpu_args(CaseContext& ctx) {
    QuadScene scene(ctx);
    rhi::BufferHandle args = ctx.buffer(64, kStorageUsage | rhi::BufferUsage::IndirectArgs, nullptr, "draw args");
    struct { uint32_t vertexCount, instanceCount, indexCount, firstIndex; } p{3, 1, 6, 0};
    rhi::DispatchState w;
    w.shader = ctx.shader("rhi_tests/write_draw_args.comp");
    w.label = "write draw args";
    w.bindings.constants.push(rhi::constants(0, p));
    w.bindings.storageBuffers.push({0, args, {}, rhi::Access::Write});
    ctx.device.dispatch(w, 1, 1, 1);
    // Indexed: the whole quad.
    ctx.check(ctx.device.drawIndirect(scene.state, args, 16, true), "indexed drawIndirect");
    std::vector<uint8_t> image;
    ctx.check(scene.leftHalfRed(ctx, &image), "indexed indirect draw did not cover exactly the left half");
    ctx.output("indexed", image);
    // Non-indexed: the first triangle (vertices 0, 1, 2) covers the lower-left triangle of the quad.
    ctx.check(ctx.device.drawIndirect(scene.state, args, 0, false), "drawIndirect");
    image = ctx.readTexture(scene.target);
    ctx.check(image[(0 * 16 + 0) * 4] == 255 && image[(15 * 16 + 7) * 4] == 0 && image[(0 * 16 + 8) * 4] == 0,
              "non-indexed indirect draw: one triangle expected (row 0 = clip y -1)");
    ctx.output("triangle", image);
}

static void draw_indexed_u16_u32(CaseContext& ctx) {
    QuadScene scene(ctx);
    std::vector<uint8_t> image;
    ctx.check(ctx.device.drawIndexed(scene.state, {6, 1, 0, 0, 0}), "drawIndexed u32");
    ctx.check(scene.leftHalfRed(ctx, &image), "u32 indices");
    ctx.output("u32", image);
    // U16 indices at a byte offset of 4, with vertexOffset -1 against indices that start at 1.
    const uint16_t idx16[8] = {0xFFFF, 0xFFFF, 1, 2, 3, 3, 2, 4};
    scene.state.indexBuffer = {ctx.buffer(sizeof(idx16), rhi::BufferUsage::Index, idx16, "u16 indices"), 4,
                               rhi::IndexFormat::U16};
    ctx.check(ctx.device.drawIndexed(scene.state, {6, 1, 0, -1, 0}), "drawIndexed u16");
    ctx.check(scene.leftHalfRed(ctx, &image), "u16 indices with offset and vertexOffset");
    ctx.output("u16", image);
}

void appendIndirectCases(std::vector<Case>& out) {
    out.insert(out.end(), {
        BL_CASE(indirect_dispatch_from_gpu_args, "dispatchIndirect with arguments written by a dispatch, at a non-zero offset"),
        BL_CASE(indirect_draw_from_gpu_args, "drawIndirect (non-indexed and indexed) with arguments written by a dispatch"),
        BL_CASE(draw_indexed_u16_u32, "drawIndexed with U16 and U32 index buffers, index buffer offset, vertexOffset"),
    });
}

}  // namespace bricklight::conformance
