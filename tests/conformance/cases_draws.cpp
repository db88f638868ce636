// Draw records: depth test, blending, multiple render targets, geometry shaders, culling and the image
// origin, instancing, viewport and scissor, rendering into a mip/layer, sRGB targets, sampling in a draw.
#include <cmath>

#include "case_helpers.h"

namespace bricklight::conformance {
using rhi::Format;

namespace {
constexpr uint32_t kSize = 16;

rhi::TextureHandle colorTarget(CaseContext& ctx, Format f = Format::RGBA8_UNORM, const char* name = "color") {
    return ctx.texture(texture2D(f, kSize, kSize, rhi::TextureUsage::RenderTarget, name));
}

rhi::ColorTarget clearTo(rhi::TextureHandle t, float r, float g, float b, float a) {
    rhi::ColorTarget ct;
    ct.view = rhi::textureMip(t, 0);
    ct.load = rhi::LoadOp::Clear;
    ct.clearColor[0] = r, ct.clearColor[1] = g, ct.clearColor[2] = b, ct.clearColor[3] = a;
    return ct;
}

// A fullscreen draw of a constant colour at a depth.
struct Fullscreen {
    float color[4];
    float depth;
    float pad[3];
};

rhi::DrawCallState fullscreenState(CaseContext& ctx, const Fullscreen& params) {
    rhi::DrawCallState s;
    s.vertexShader = ctx.shader("rhi_tests/draw_fullscreen.vert");
    s.fragmentShader = ctx.shader("rhi_tests/draw_color.frag");
    s.bindings.constants.push(rhi::constants(0, params));
    s.label = "fullscreen";
    return s;
}

const uint8_t* pixel(const std::vector<uint8_t>& img, uint32_t x, uint32_t y, uint32_t bpp = 4) {
    return &img[(size_t(y) * kSize + x) * bpp];
}

// Triangle vertices: x, y, z, r, g, b, a.
rhi::BufferHandle triangle(CaseContext& ctx, const float (&v)[3][7], const char* name) {
    return ctx.buffer(sizeof(v), rhi::BufferUsage::Vertex, v, name);
}

void colorInputs(rhi::DrawCallState& s, rhi::BufferHandle vb) {
    s.vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
    s.vertexInputs.push({1, rhi::VertexFormat::Float4, 0, 12});
    s.vertexBuffers.push({vb, 0, 28, false});
}
}  // namespace

static void draw_depth_test(CaseContext& ctx) {
    rhi::TextureHandle color = colorTarget(ctx);
    rhi::TextureHandle depth = ctx.texture(texture2D(Format::D32_FLOAT, kSize, kSize, rhi::TextureUsage::DepthTarget, "depth"));
    Fullscreen near{{0, 1, 0, 1}, 0.25f, {}}, far{{1, 0, 0, 1}, 0.75f, {}};
    // Near first, then far: far fails the Less test.
    rhi::DrawCallState s = fullscreenState(ctx, near);
    s.colorTargets.push(clearTo(color, 0, 0, 0, 1));
    s.depthTarget.view = rhi::textureMip(depth, 0);
    s.depthTarget.load = rhi::LoadOp::Clear;
    s.depthTarget.clearDepth = 1.0f;
    s.depth = {true, true, rhi::CompareOp::Less};
    ctx.device.draw(s, {3});
    rhi::DrawCallState f = fullscreenState(ctx, far);
    rhi::ColorTarget keep;
    keep.view = rhi::textureMip(color, 0);
    f.colorTargets.push(keep);
    f.depthTarget.view = rhi::textureMip(depth, 0);
    f.depth = {true, true, rhi::CompareOp::Less};
    ctx.device.draw(f, {3});
    auto img = ctx.readTexture(color);
    ctx.check(pixel(img, 3, 4)[1] == 255 && pixel(img, 3, 4)[0] == 0, "the far draw passed the depth test");
    auto d = ctx.readTexture(depth);
    float dv;
    std::memcpy(&dv, d.data() + 4 * (7 * kSize + 7), 4);
    ctx.check(dv == 0.25f, "depth buffer holds " + std::to_string(dv) + " (depth range [0,1], no remap)");
    // With Greater the far draw wins.
    f.depth.compare = rhi::CompareOp::Greater;
    ctx.device.draw(f, {3});
    img = ctx.readTexture(color);
    ctx.check(pixel(img, 3, 4)[0] == 255, "Greater: the far draw should pass");
    ctx.output("color", img);
    ctx.output("depth", ctx.readTexture(depth));
}

static void draw_blending(CaseContext& ctx) {
    rhi::TextureHandle color = colorTarget(ctx);
    Fullscreen p{{0.5f, 0.25f, 0.0f, 0.5f}, 0.5f, {}};
    rhi::DrawCallState s = fullscreenState(ctx, p);
    rhi::ColorTarget ct = clearTo(color, 0.2f, 0.2f, 0.2f, 1.0f);
    ct.blend.enable = true;
    ct.blend.srcColor = rhi::BlendFactor::SrcAlpha;
    ct.blend.dstColor = rhi::BlendFactor::OneMinusSrcAlpha;
    ct.blend.srcAlpha = rhi::BlendFactor::One;
    ct.blend.dstAlpha = rhi::BlendFactor::Zero;
    s.colorTargets.push(ct);
    ctx.device.draw(s, {3});
    auto img = ctx.readTexture(color);
    // 0.5 * 0.5 + 0.2 * 0.5 = 0.35 -> 89; 0.25*0.5 + 0.1 = 0.225 -> 57; 0.1 -> 26; alpha 0.5 -> 128.
    const uint8_t* px = pixel(img, 5, 5);
    ctx.check(std::abs(px[0] - 89) <= 1 && std::abs(px[1] - 57) <= 1 && std::abs(px[2] - 26) <= 1 && std::abs(px[3] - 128) <= 1,
              "alpha blending result " + std::to_string(px[0]) + "," + std::to_string(px[1]) + "," + std::to_string(px[2]));
    ctx.output("alpha", img, {Tolerance::Kind::Unorm8, 1});
    // Additive on top, red and alpha masked out.
    s.colorTargets[0].load = rhi::LoadOp::Load;
    s.colorTargets[0].blend = rhi::BlendState{true, rhi::BlendFactor::One, rhi::BlendFactor::One, rhi::BlendOp::Add,
                                              rhi::BlendFactor::One, rhi::BlendFactor::One, rhi::BlendOp::Add, 0x6};
    ctx.device.draw(s, {3});
    img = ctx.readTexture(color);
    px = pixel(img, 5, 5);
    ctx.check(std::abs(px[0] - 89) <= 1 && std::abs(px[1] - 121) <= 1 && std::abs(px[2] - 26) <= 1 && std::abs(px[3] - 128) <= 1,
              "additive with write mask GB: " + std::to_string(px[0]) + "," + std::to_string(px[1]));
    // Max op.
    s.colorTargets[0].blend = rhi::BlendState{true, rhi::BlendFactor::One, rhi::BlendFactor::One, rhi::BlendOp::Max,
                                              rhi::BlendFactor::One, rhi::BlendFactor::One, rhi::BlendOp::Min, 0xF};
    ctx.device.draw(s, {3});
    img = ctx.readTexture(color);
    px = pixel(img, 5, 5);
    ctx.check(std::abs(px[0] - 128) <= 1 && std::abs(px[1] - 121) <= 1 && std::abs(px[3] - 128) <= 1, "max/min ops");
    ctx.output("ops", img, {Tolerance::Kind::Unorm8, 1});
}

static void draw_multiple_render_targets(CaseContext& ctx) {
    rhi::TextureHandle c0 = colorTarget(ctx, Format::RGBA8_UNORM, "albedo");
    rhi::TextureHandle c1 = colorTarget(ctx, Format::R32_FLOAT, "x");
    rhi::TextureHandle c2 = colorTarget(ctx, Format::R32_UINT, "y");
    Fullscreen p{{0, 0, 1, 1}, 0.5f, {}};
    rhi::DrawCallState s = fullscreenState(ctx, p);
    s.fragmentShader = ctx.shader("rhi_tests/draw_mrt.frag");
    s.colorTargets.push(clearTo(c0, 0, 0, 0, 0));
    s.colorTargets.push(clearTo(c1, 0, 0, 0, 0));
    s.colorTargets.push(clearTo(c2, 0, 0, 0, 0));
    ctx.device.draw(s, {3});
    auto a = ctx.readTexture(c0), x = ctx.readTexture(c1), y = ctx.readTexture(c2);
    float xv;
    uint32_t yv;
    std::memcpy(&xv, pixel(x, 6, 11), 4);
    std::memcpy(&yv, pixel(y, 6, 11), 4);
    ctx.check(pixel(a, 6, 11)[2] == 255, "target 0");
    ctx.check(xv == 6.5f, "target 1 holds gl_FragCoord.x = " + std::to_string(xv));
    ctx.check(yv == 11, "target 2 holds the memory row (gl_FragCoord.y) = " + std::to_string(yv));
    ctx.output("albedo", a);
    ctx.output("x", x);
    ctx.output("y", y);
}

static void draw_geometry_shader(CaseContext& ctx) {
    if (!ctx.device.capabilities().geometryShader) return ctx.fail("device reports no geometry shader support");
    rhi::TextureHandle color = colorTarget(ctx);
    const float pts[2][7] = {{-0.5f, -0.5f, 0.5f, 1, 0, 0, 1}, {0.5f, 0.5f, 0.5f, 0, 1, 0, 1}};
    rhi::DrawCallState s;
    s.vertexShader = ctx.shader("rhi_tests/draw_points.vert");
    s.geometryShader = ctx.shader("rhi_tests/draw_points_to_quads.geom");
    s.fragmentShader = ctx.shader("rhi_tests/draw_color.frag");
    s.topology = rhi::PrimitiveTopology::PointList;
    s.vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
    s.vertexInputs.push({1, rhi::VertexFormat::Float4, 0, 12});
    s.vertexBuffers.push({ctx.buffer(sizeof(pts), rhi::BufferUsage::Vertex, pts, "points"), 0, 28, false});
    const float halfSize[4] = {0.25f, 0.25f, 0, 0};
    s.bindings.constants.push(rhi::constants(0, halfSize));
    s.colorTargets.push(clearTo(color, 0, 0, 0, 1));
    s.label = "points to quads";
    ctx.device.draw(s, {2});
    auto img = ctx.readTexture(color);
    // Quad 1 covers clip [-0.75, -0.25] -> pixels 2..5; quad 2 pixels 10..13.
    ctx.check(pixel(img, 3, 3)[0] == 255 && pixel(img, 12, 12)[1] == 255, "expanded quads present");
    ctx.check(pixel(img, 8, 8)[0] == 0 && pixel(img, 8, 8)[1] == 0 && pixel(img, 1, 1)[0] == 0, "nothing outside the quads");
    ctx.output("image", img);
}

static void draw_culling_and_origin(CaseContext& ctx) {
    rhi::TextureHandle color = colorTarget(ctx);
    // Triangle a, in framebuffer coordinates (x right, y down, row 0 first): (0,0) -> (8,0) -> (0,8), which
    // turns clockwise on screen. Vulkan's rule: area a = -1/2 sum(x_i y_i+1 - x_i+1 y_i) = -32 < 0, so it is
    // front-facing only with FrontFace::Clockwise. GL computes the area without the minus sign; the GL
    // backend must invert glFrontFace to match.
    const float a[3][7] = {{-1, -1, 0.5f, 1, 0, 0, 1}, {0, -1, 0.5f, 1, 0, 0, 1}, {-1, 0, 0.5f, 1, 0, 0, 1}};
    const float b[3][7] = {{1, 1, 0.5f, 0, 1, 0, 1}, {0, 1, 0.5f, 0, 1, 0, 1}, {1, 0, 0.5f, 0, 1, 0, 1}};
    rhi::DrawCallState s;
    s.vertexShader = ctx.shader("rhi_tests/draw_color.vert");
    s.fragmentShader = ctx.shader("rhi_tests/draw_color.frag");
    colorInputs(s, triangle(ctx, a, "triangle a"));
    s.colorTargets.push(clearTo(color, 0, 0, 0, 1));
    s.raster.cull = rhi::CullMode::None;
    ctx.device.draw(s, {3});
    auto img = ctx.readTexture(color);
    // Triangle a lies at clip y in [-1, 0]: memory rows 0..7, columns 0..7.
    ctx.check(pixel(img, 1, 1)[0] == 255 && pixel(img, 1, 14)[0] == 0, "clip y -1 must be memory row 0");
    s.raster.cull = rhi::CullMode::Back;
    s.raster.frontFace = rhi::FrontFace::CounterClockwise;
    s.colorTargets[0] = clearTo(color, 0, 0, 0, 1);
    ctx.device.draw(s, {3});
    bool aVisibleCcw = ctx.readTexture(color)[(1 * kSize + 1) * 4] == 255;
    s.raster.frontFace = rhi::FrontFace::Clockwise;
    ctx.device.draw(s, {3});
    bool aVisibleCw = ctx.readTexture(color)[(1 * kSize + 1) * 4] == 255;
    ctx.check(aVisibleCcw != aVisibleCw, "back-face culling must keep the triangle for exactly one front-face setting");
    ctx.check(aVisibleCw && !aVisibleCcw, "triangle a (clockwise on screen) must be front-facing with FrontFace::Clockwise only");
    rhi::DrawCallState t = s;
    t.vertexBuffers[0].buffer = triangle(ctx, b, "triangle b");
    t.raster.frontFace = rhi::FrontFace::Clockwise;
    t.colorTargets[0] = clearTo(color, 0, 0, 0, 1);
    ctx.device.draw(t, {3});
    img = ctx.readTexture(color);
    ctx.check(pixel(img, 14, 14)[1] == 255, "triangle b (same winding, opposite corner) visible at the last rows");
    ctx.output("image", img);
}

static void draw_instancing(CaseContext& ctx) {
    rhi::TextureHandle color = colorTarget(ctx);
    const float quad[6][2] = {{0, 0}, {0.25f, 0}, {0, 0.25f}, {0, 0.25f}, {0.25f, 0}, {0.25f, 0.25f}};
    // offset x, y, colour rgba for 4 instances; instance 0 is skipped through firstInstance 1.
    const float inst[4][6] = {{-1, -1, 1, 1, 1, 1}, {-1, -1, 1, 0, 0, 1}, {0, 0, 0, 1, 0, 1}, {0.5f, -1, 0, 0, 1, 1}};
    rhi::DrawCallState s;
    s.vertexShader = ctx.shader("rhi_tests/draw_instanced.vert");
    s.fragmentShader = ctx.shader("rhi_tests/draw_color.frag");
    s.vertexInputs.push({0, rhi::VertexFormat::Float2, 0, 0});
    s.vertexInputs.push({1, rhi::VertexFormat::Float2, 1, 0});
    s.vertexInputs.push({2, rhi::VertexFormat::Float4, 1, 8});
    s.vertexBuffers.push({ctx.buffer(sizeof(quad), rhi::BufferUsage::Vertex, quad, "quad"), 0, 8, false});
    s.vertexBuffers.push({ctx.buffer(sizeof(inst), rhi::BufferUsage::Vertex, inst, "instances"), 0, 24, true});
    s.colorTargets.push(clearTo(color, 0, 0, 0, 1));
    s.label = "instances";
    ctx.device.draw(s, {6, 3, 0, 1});
    auto img = ctx.readTexture(color);
    // Instance 1 (red) at clip (-1,-1): pixels 0..1; instance 2 (green) at (0,0): pixels 8..9; instance 3 (blue).
    ctx.check(pixel(img, 0, 0)[0] == 255 && pixel(img, 0, 0)[1] == 0 && pixel(img, 0, 0)[2] == 0,
              "firstInstance 1: instance 0 (white) must not be drawn; instance 1 red");
    ctx.check(pixel(img, 8, 8)[1] == 255, "instance 2 green");
    ctx.check(pixel(img, 12, 0)[2] == 255, "instance 3 blue");
    ctx.output("image", img);
}

static void draw_viewport_scissor(CaseContext& ctx) {
    rhi::TextureHandle color = colorTarget(ctx);
    Fullscreen p{{1, 1, 0, 1}, 0.5f, {}};
    rhi::DrawCallState s = fullscreenState(ctx, p);
    s.colorTargets.push(clearTo(color, 0, 0, 0, 1));
    s.viewport = {4, 2, 8, 8, 0, 1};
    s.scissor = {0, 0, 10, 16};
    ctx.device.draw(s, {3});
    auto img = ctx.readTexture(color);
    ctx.check(pixel(img, 4, 2)[0] == 255 && pixel(img, 9, 9)[0] == 255, "inside viewport and scissor");
    ctx.check(pixel(img, 3, 2)[0] == 0 && pixel(img, 4, 1)[0] == 0 && pixel(img, 4, 10)[0] == 0, "outside the viewport");
    ctx.check(pixel(img, 10, 5)[0] == 0 && pixel(img, 11, 5)[0] == 0, "outside the scissor");
    ctx.output("image", img);
}

static void draw_into_mip_and_layer(CaseContext& ctx) {
    rhi::TextureDesc d = texture2D(Format::RGBA8_UNORM, kSize, kSize, rhi::TextureUsage::RenderTarget, "array target", 2);
    d.dimension = rhi::TextureDimension::Texture2DArray;
    d.depthOrLayers = 3;
    rhi::TextureHandle tex = ctx.texture(d);
    ctx.device.clearTexture(tex, 0, 2, rhi::ClearValue{{0, 0, 0, 0}});
    Fullscreen p{{0.5f, 1, 0, 1}, 0.5f, {}};
    rhi::DrawCallState s = fullscreenState(ctx, p);
    rhi::ColorTarget ct;
    ct.view = rhi::textureMip(tex, 1);
    ct.view.baseLayer = 2;
    ct.view.layerCount = 1;
    ct.load = rhi::LoadOp::Load;
    s.colorTargets.push(ct);
    ctx.device.draw(s, {3});
    auto l2 = ctx.readTexture(tex, {1, 2, 1});
    auto l1 = ctx.readTexture(tex, {1, 1, 1});
    auto m0 = ctx.readTexture(tex, {0, 2, 1});
    // 0.5 * 255 = 127.5: drivers may round either way (NVIDIA gives 127, llvmpipe 128).
    ctx.check(l2.size() == 8 * 8 * 4 && std::abs(int(l2[0]) - 128) <= 1 && l2[1] == 255 && l2[(8 * 8 - 1) * 4 + 1] == 255,
              "mip 1 layer 2 drawn (got " + std::to_string(l2.empty() ? -1 : int(l2[0])) + ")");
    ctx.check(l1[1] == 0 && m0[1] == 0, "other subresources untouched");
    ctx.output("mip1layer2", l2, {Tolerance::Kind::Unorm8, 1});
}

static void draw_srgb_target(CaseContext& ctx) {
    rhi::TextureHandle color = colorTarget(ctx, Format::RGBA8_SRGB, "srgb");
    Fullscreen p{{0.5f, 0.2140f, 1.0f, 0.5f}, 0.5f, {}};
    rhi::DrawCallState s = fullscreenState(ctx, p);
    s.colorTargets.push(clearTo(color, 0, 0, 0, 0));
    ctx.device.draw(s, {3});
    auto img = ctx.readTexture(color);
    const uint8_t* px = pixel(img, 2, 2);
    // linear 0.5 -> sRGB 188; 0.214 -> 128; alpha stays linear.
    ctx.check(std::abs(px[0] - 188) <= 1 && std::abs(px[1] - 128) <= 1 && px[2] == 255 && std::abs(px[3] - 128) <= 1,
              "sRGB encode " + std::to_string(px[0]) + "," + std::to_string(px[1]));
    ctx.output("image", img, {Tolerance::Kind::Unorm8, 1});
}

static void draw_samples_texture_written_by_compute(CaseContext& ctx) {
    rhi::TextureHandle src = ctx.texture(texture2D(Format::RGBA8_UNORM, kSize, kSize,
                                                   rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled, "computed"));
    struct { int32_t w, h; uint32_t seed; } wp{int32_t(kSize), int32_t(kSize), 11};
    rhi::DispatchState w;
    w.shader = ctx.shader("rhi_tests/image_write_rgba8.comp");
    w.label = "produce";
    w.bindings.constants.push(rhi::constants(0, wp));
    w.bindings.storageImages.push({0, rhi::textureMip(src, 0), rhi::Access::Write});
    ctx.device.dispatch(w, 2, 2, 1);
    rhi::TextureHandle color = colorTarget(ctx);
    Fullscreen p{{1, 1, 1, 1}, 0.5f, {}};
    rhi::DrawCallState s = fullscreenState(ctx, p);
    s.fragmentShader = ctx.shader("rhi_tests/draw_sampled.frag");
    const float inv[4] = {1.0f / kSize, 1.0f / kSize, 0, 0};
    s.bindings.constants.push(rhi::constants(1, inv));
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "nearest";
    s.bindings.textures.push({0, rhi::wholeTexture(src), ctx.sampler(sd)});
    s.colorTargets.push(clearTo(color, 0, 0, 0, 0));
    ctx.device.draw(s, {3});
    auto img = ctx.readTexture(color);
    auto ref = ctx.readTexture(src);
    ctx.check(img == ref, "the draw copied the computed texture texel for texel");
    ctx.output("image", img);
}

void appendDrawCases(std::vector<Case>& out) {
    out.insert(out.end(), {
        BL_CASE(draw_depth_test, "DepthTarget load Clear, DepthState test/write/compare, D32_FLOAT readback"),
        BL_CASE(draw_blending, "BlendState: additive, alpha blending, min/max ops, write mask"),
        BL_CASE(draw_multiple_render_targets, "three colour targets of different formats (RGBA8, R32_FLOAT, R32_UINT) in one draw"),
        BL_CASE(draw_geometry_shader, "geometryShader: points expanded to quads, PointList topology"),
        BL_CASE(draw_culling_and_origin, "RasterState cull/frontFace (Vulkan rule), image origin: clip y -1 is memory row 0"),
        BL_CASE(draw_instancing, "per-instance vertex buffers (perInstance), instanceCount, firstInstance, Float2 inputs"),
        BL_CASE(draw_viewport_scissor, "Viewport (offset, size, depth range) and ScissorRect"),
        BL_CASE(draw_into_mip_and_layer, "ColorTarget view selecting mip 1 of layer 2 of a 2D array"),
        BL_CASE(draw_srgb_target, "RGBA8_SRGB colour target: linear shader output is encoded to sRGB on write"),
        BL_CASE(draw_samples_texture_written_by_compute, "a draw's bindings (textures + constants in vertex and fragment stages) reading a compute result"),
    });
}

}  // namespace bricklight::conformance
