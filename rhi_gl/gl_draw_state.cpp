#include "gl_draw_state.h"

namespace bricklight::gl::detail {

GLuint FramebufferCache::get(const Functions& gl, const Attachment* colors, uint32_t colorCount,
                             const Attachment& depth, std::string* error) {
    std::vector<uint32_t> key;
    std::vector<uint32_t> ids;
    auto add = [&](const Attachment& a) {
        key.insert(key.end(), {a.textureId, a.texture, uint32_t(a.level), uint32_t(a.layer)});
        if (a.texture) ids.push_back(a.textureId);
    };
    for (uint32_t i = 0; i < colorCount; ++i) add(colors[i]);
    key.push_back(0xFFFFFFFFu);  // separates the colours from the depth attachment
    add(depth);
    if (auto it = fbos_.find(key); it != fbos_.end()) return it->second.fbo;

    GLuint fbo = 0;
    gl.CreateFramebuffers(1, &fbo);
    auto attach = [&](GLenum point, const Attachment& a) {
        if (a.layer < 0) gl.NamedFramebufferTexture(fbo, point, a.texture, a.level);
        else gl.NamedFramebufferTextureLayer(fbo, point, a.texture, a.level, a.layer);
    };
    GLenum drawBuffers[8];
    for (uint32_t i = 0; i < colorCount; ++i) {
        attach(GL_COLOR_ATTACHMENT0 + i, colors[i]);
        drawBuffers[i] = GL_COLOR_ATTACHMENT0 + i;  // fragment output location i -> colour target i
    }
    if (depth.texture) attach(GL_DEPTH_ATTACHMENT, depth);
    if (colorCount) {
        gl.NamedFramebufferDrawBuffers(fbo, GLsizei(colorCount), drawBuffers);
    } else {
        GLenum none = GL_NONE;
        gl.NamedFramebufferDrawBuffers(fbo, 1, &none);
    }
    gl.NamedFramebufferReadBuffer(fbo, GL_NONE);
    GLenum status = gl.CheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        gl.DeleteFramebuffers(1, &fbo);
        *error = "the render targets do not form a complete framebuffer (status " + hex(status) + ")";
        return 0;
    }
    fbos_.emplace(std::move(key), Entry{fbo, std::move(ids)});
    return fbo;
}

void FramebufferCache::forget(const Functions& gl, uint32_t textureId) {
    for (auto it = fbos_.begin(); it != fbos_.end();) {
        bool uses = false;
        for (uint32_t id : it->second.textureIds) uses |= id == textureId;
        if (uses) {
            gl.DeleteFramebuffers(1, &it->second.fbo);
            it = fbos_.erase(it);
        } else {
            ++it;
        }
    }
}

void FramebufferCache::clear(const Functions& gl) {
    for (auto& [k, e] : fbos_) gl.DeleteFramebuffers(1, &e.fbo);
    fbos_.clear();
}

GLuint VertexArrayCache::get(const Functions& gl, const rhi::DrawCallState& state) {
    std::vector<uint32_t> key;
    for (const rhi::VertexInput& in : state.vertexInputs)
        key.insert(key.end(), {in.location, uint32_t(in.format), in.bufferIndex, in.offset});
    key.push_back(0xFFFFFFFFu);
    for (const rhi::VertexBufferBinding& b : state.vertexBuffers) key.push_back(b.perInstance ? 1u : 0u);
    if (auto it = vaos_.find(key); it != vaos_.end()) return it->second;

    GLuint vao = 0;
    gl.CreateVertexArrays(1, &vao);
    using VF = rhi::VertexFormat;
    for (const rhi::VertexInput& in : state.vertexInputs) {
        gl.EnableVertexArrayAttrib(vao, in.location);
        switch (in.format) {
            case VF::Float1:
            case VF::Float2:
            case VF::Float3:
            case VF::Float4:
                gl.VertexArrayAttribFormat(vao, in.location, GLint(in.format) - GLint(VF::Float1) + 1, GL_FLOAT,
                                           GL_FALSE, in.offset);
                break;
            case VF::UByte4Norm:
                gl.VertexArrayAttribFormat(vao, in.location, 4, GL_UNSIGNED_BYTE, GL_TRUE, in.offset);
                break;
            case VF::UInt1: gl.VertexArrayAttribIFormat(vao, in.location, 1, GL_UNSIGNED_INT, in.offset); break;
            case VF::Half4: gl.VertexArrayAttribFormat(vao, in.location, 4, GL_HALF_FLOAT, GL_FALSE, in.offset); break;
        }
        gl.VertexArrayAttribBinding(vao, in.location, in.bufferIndex);
    }
    for (uint32_t i = 0; i < state.vertexBuffers.size(); ++i)
        gl.VertexArrayBindingDivisor(vao, i, state.vertexBuffers[i].perInstance ? 1 : 0);
    gl.ObjectLabel(GL_VERTEX_ARRAY, vao, -1, "bricklight vertex layout");
    vaos_.emplace(std::move(key), vao);
    return vao;
}

void VertexArrayCache::clear(const Functions& gl) {
    for (auto& [k, vao] : vaos_) gl.DeleteVertexArrays(1, &vao);
    vaos_.clear();
}

GLenum compareFunc(rhi::CompareOp op) {
    using C = rhi::CompareOp;
    switch (op) {
        case C::Never: return GL_NEVER;
        case C::Less: return GL_LESS;
        case C::Equal: return GL_EQUAL;
        case C::LessOrEqual: return GL_LEQUAL;
        case C::Greater: return GL_GREATER;
        case C::NotEqual: return GL_NOTEQUAL;
        case C::GreaterOrEqual: return GL_GEQUAL;
        case C::Always: return GL_ALWAYS;
    }
    return GL_ALWAYS;
}

GLenum topologyMode(rhi::PrimitiveTopology topology) {
    using T = rhi::PrimitiveTopology;
    switch (topology) {
        case T::TriangleList: return GL_TRIANGLES;
        case T::TriangleStrip: return GL_TRIANGLE_STRIP;
        case T::LineList: return GL_LINES;
        case T::PointList: return GL_POINTS;
    }
    return GL_TRIANGLES;
}

namespace {
GLenum blendFactor(rhi::BlendFactor f) {
    using B = rhi::BlendFactor;
    switch (f) {
        case B::Zero: return GL_ZERO;
        case B::One: return GL_ONE;
        case B::SrcColor: return GL_SRC_COLOR;
        case B::OneMinusSrcColor: return GL_ONE_MINUS_SRC_COLOR;
        case B::DstColor: return GL_DST_COLOR;
        case B::OneMinusDstColor: return GL_ONE_MINUS_DST_COLOR;
        case B::SrcAlpha: return GL_SRC_ALPHA;
        case B::OneMinusSrcAlpha: return GL_ONE_MINUS_SRC_ALPHA;
        case B::DstAlpha: return GL_DST_ALPHA;
        case B::OneMinusDstAlpha: return GL_ONE_MINUS_DST_ALPHA;
    }
    return GL_ONE;
}
GLenum blendOp(rhi::BlendOp op) {
    using B = rhi::BlendOp;
    switch (op) {
        case B::Add: return GL_FUNC_ADD;
        case B::Subtract: return GL_FUNC_SUBTRACT;
        case B::ReverseSubtract: return GL_FUNC_REVERSE_SUBTRACT;
        case B::Min: return GL_MIN;
        case B::Max: return GL_MAX;
    }
    return GL_FUNC_ADD;
}
}  // namespace

void applyDrawState(const Functions& gl, const rhi::DrawCallState& s, uint32_t targetWidth, uint32_t targetHeight,
                    uint32_t clipDistances, bool srgbTarget) {
    // Vulkan conventions: depth range [0,1]; window y = 0 is memory row 0 in both APIs, so lower-left
    // origin keeps clip y = -1 on row 0 exactly as Vulkan's viewport does.
    gl.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    const rhi::Viewport& v = s.viewport;
    if (v.width == 0.0f) gl.ViewportIndexedf(0, 0.0f, 0.0f, float(targetWidth), float(targetHeight));
    else gl.ViewportIndexedf(0, v.x, v.y, v.width, v.height);
    gl.DepthRangeIndexed(0, v.minDepth, v.maxDepth);
    if (s.scissor.width == 0) {
        gl.Disable(GL_SCISSOR_TEST);
    } else {
        gl.Enable(GL_SCISSOR_TEST);
        gl.ScissorIndexed(0, s.scissor.x, s.scissor.y, GLsizei(s.scissor.width), GLsizei(s.scissor.height));
    }

    // Raster. Vulkan's polygon area has the opposite sign of GL's for the same window coordinates, so a
    // record's counter-clockwise front face is GL_CW (and vice versa): culling and gl_FrontFacing match.
    gl.FrontFace(s.raster.frontFace == rhi::FrontFace::CounterClockwise ? GL_CW : GL_CCW);
    if (s.raster.cull == rhi::CullMode::None) {
        gl.Disable(GL_CULL_FACE);
    } else {
        gl.Enable(GL_CULL_FACE);
        gl.CullFace(s.raster.cull == rhi::CullMode::Front ? GL_FRONT : GL_BACK);
    }
    if (s.raster.depthClamp) gl.Enable(GL_DEPTH_CLAMP);
    else gl.Disable(GL_DEPTH_CLAMP);
    if (s.raster.depthBiasConstant != 0.0f || s.raster.depthBiasSlope != 0.0f) {
        gl.Enable(GL_POLYGON_OFFSET_FILL);
        gl.PolygonOffset(s.raster.depthBiasSlope, s.raster.depthBiasConstant);
    } else {
        gl.Disable(GL_POLYGON_OFFSET_FILL);
    }
    gl.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    gl.ProvokingVertex(GL_FIRST_VERTEX_CONVENTION);  // Vulkan's: flat (integer) varyings match
    gl.Enable(GL_PROGRAM_POINT_SIZE);                // Vulkan: the shader's gl_PointSize
    gl.LineWidth(1.0f);
    gl.Disable(GL_PRIMITIVE_RESTART);
    gl.Disable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    gl.Disable(GL_RASTERIZER_DISCARD);
    gl.Disable(GL_STENCIL_TEST);
    gl.Disable(GL_DITHER);
    gl.Disable(GL_COLOR_LOGIC_OP);
    gl.Disable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    for (uint32_t i = 0; i < 8; ++i) {
        if (i < clipDistances) gl.Enable(GL_CLIP_DISTANCE0 + i);
        else gl.Disable(GL_CLIP_DISTANCE0 + i);
    }

    // Depth: with the test off GL writes no depth either, which is Vulkan's rule too.
    if (s.depth.testEnable) {
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(compareFunc(s.depth.compare));
    } else {
        gl.Disable(GL_DEPTH_TEST);
    }
    gl.DepthMask(s.depth.writeEnable ? GL_TRUE : GL_FALSE);

    // Blend per colour target.
    for (uint32_t i = 0; i < s.colorTargets.size(); ++i) {
        const rhi::BlendState& b = s.colorTargets[i].blend;
        if (b.enable) {
            gl.Enablei(GL_BLEND, i);
            gl.BlendFuncSeparatei(i, blendFactor(b.srcColor), blendFactor(b.dstColor), blendFactor(b.srcAlpha),
                                  blendFactor(b.dstAlpha));
            gl.BlendEquationSeparatei(i, blendOp(b.colorOp), blendOp(b.alphaOp));
        } else {
            gl.Disablei(GL_BLEND, i);
        }
        gl.ColorMaski(i, (b.writeMask & 1) != 0, (b.writeMask & 2) != 0, (b.writeMask & 4) != 0,
                      (b.writeMask & 8) != 0);
    }
    // sRGB targets encode on write (and blend in linear), as Vulkan does for sRGB attachments.
    if (srgbTarget) gl.Enable(GL_FRAMEBUFFER_SRGB);
    else gl.Disable(GL_FRAMEBUFFER_SRGB);
    gl.Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);  // Vulkan always filters cube maps seamlessly
}

}  // namespace bricklight::gl::detail
