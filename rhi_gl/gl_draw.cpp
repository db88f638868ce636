// draw / drawIndexed / drawIndirect: validate the record, pick (or make) the program, VAO and FBO, clear
// per LoadOp, set the fixed-function state, bind, draw, and leave FBO 0, program 0, VAO 0 bound.
#include <algorithm>
#include <cmath>

#include "../rhi/size_math.h"
#include "gl_device.h"
#include "gl_formats.h"

namespace bricklight::gl::detail {

using namespace rhi;

struct Device::DrawPlan {
    ShaderRecord* vs = nullptr;
    ShaderRecord* gs = nullptr;
    ShaderRecord* fs = nullptr;
    GLuint program = 0;
    BindingPlan bindings;
    GLuint fbo = 0;
    uint32_t width = 0, height = 0;
    bool srgb = false;
    GLuint vao = 0;
    BufferRecord* vertexBuffers[kMaxVertexBuffers] = {};
    BufferRecord* indexBuffer = nullptr;
};

namespace {
uint32_t indexBytes(IndexFormat f) { return f == IndexFormat::U16 ? 2 : 4; }
GLenum indexType(IndexFormat f) { return f == IndexFormat::U16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT; }
}  // namespace

bool Device::prepareTargets(const Call& call, const DrawCallState& s, DrawPlan* plan) {
    if (s.colorTargets.size() > caps_.limits.maxColorTargets)
        return fail(call, "colorTargets: " + std::to_string(s.colorTargets.size()) + " targets exceed maxColorTargets " +
                              std::to_string(caps_.limits.maxColorTargets));
    if (s.colorTargets.empty() && !s.depthTarget.view.texture)
        return fail(call, "no render target: give at least one colour target or a depth target");
    Attachment colors[kMaxColorTargets];
    Attachment depth;
    auto attachment = [&](const std::string& fieldIn, const TextureView& view, bool isDepth, Attachment* out) {
        TextureRecord* t = texture(view.texture, call, fieldIn + ".view.texture");
        if (!t) return false;
        const std::string field = fieldIn + " " + detail::describe(*t);
        ResolvedView v;
        if (!resolveView(call, field, *t, view, &v)) return false;
        if (isDepth) {
            if (!(t->desc.usage & TextureUsage::DepthTarget))
                return fail(call, field + ": was not created with TextureUsage::DepthTarget");
        } else {
            if (!(t->desc.usage & TextureUsage::RenderTarget))
                return fail(call, field + ": was not created with TextureUsage::RenderTarget");
            if (!caps_.supports(v.format, FormatSupport::RenderTarget))
                return fail(call, field + ": format " + formatName(v.format) + " cannot be a render target on this device");
        }
        const uint32_t w = mipExtent(t->desc.width, v.baseMip), h = mipExtent(t->desc.height, v.baseMip);
        if (plan->width == 0) plan->width = w, plan->height = h;
        else if (w != plan->width || h != plan->height)
            return fail(call, field + ": size " + std::to_string(w) + "x" + std::to_string(h) + " differs from the other targets' " +
                                  std::to_string(plan->width) + "x" + std::to_string(plan->height));
        out->textureId = t->id;
        if (v.format == t->desc.format) {
            out->texture = t->name;
            out->level = GLint(v.baseMip);
            out->layer = t->desc.dimension == TextureDimension::Texture2D ? -1 : GLint(v.baseLayer);
        } else {
            if (t->desc.dimension == TextureDimension::Texture3D)
                return fail(call, field + ": a 3D texture cannot be rendered through a format-reinterpreting view");
            ResolvedView one{v.format, v.baseMip, 1, v.baseLayer, 1};
            std::string error;
            out->texture = views_.get(gl, *t, GL_TEXTURE_2D, one, &error);
            if (!out->texture) return fail(call, field + ": " + error);
            out->level = 0;
            out->layer = -1;
        }
        plan->srgb |= v.format == Format::RGBA8_SRGB;
        barriers_.require(&plan->bindings.barriers, t->lastShaderWrite, GL_FRAMEBUFFER_BARRIER_BIT);
        return true;
    };
    for (uint32_t i = 0; i < s.colorTargets.size(); ++i) {
        const ColorTarget& c = s.colorTargets[i];
        const std::string field = "colorTargets[" + std::to_string(i) + "]";
        if (!attachment(field, c.view, false, &colors[i])) return false;
        const Format f = c.view.format == Format::Unknown ? textures_.at(c.view.texture.id).desc.format : c.view.format;
        if (c.blend.enable && !caps_.supports(f, FormatSupport::Blendable))
            return fail(call, field + ": blending is enabled but format " + formatName(f) + " is not blendable");
    }
    if (s.depthTarget.view.texture) {
        if (!attachment("depthTarget", s.depthTarget.view, true, &depth)) return false;
    } else if (s.depth.testEnable || s.depth.writeEnable) {
        return fail(call, "depth: test or write enabled but there is no depth target");
    }
    const Viewport& v = s.viewport;
    if (v.width != 0.0f && !(v.height > 0.0f && v.width > 0.0f))
        return fail(call, "viewport: width and height must both be positive (or width 0 for the whole target)");
    // What Vulkan requires too (both backends refuse the same records): finite, depths in [0, 1].
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.width) || !std::isfinite(v.height))
        return fail(call, "viewport: x, y, width and height must be finite");
    if (!(v.minDepth >= 0.0f && v.minDepth <= 1.0f && v.maxDepth >= 0.0f && v.maxDepth <= 1.0f))
        return fail(call, "viewport: minDepth and maxDepth must be in [0, 1]");
    if (!std::isfinite(s.raster.depthBiasConstant) || !std::isfinite(s.raster.depthBiasSlope))
        return fail(call, "raster: depthBiasConstant and depthBiasSlope must be finite");
    std::string error;
    plan->fbo = framebuffers_.get(gl, colors, s.colorTargets.size(), depth, &error);
    if (!plan->fbo) return fail(call, "colorTargets/depthTarget: " + error);
    return true;
}

bool Device::prepareDraw(const Call& call, const DrawCallState& s, DrawKind kind, DrawPlan* plan) {
    plan->vs = shader(s.vertexShader, call, "vertexShader");
    if (!plan->vs) return false;
    if (plan->vs->blob->stage != ShaderStage::Vertex) return fail(call, "vertexShader: " + detail::describe(*plan->vs) + " is not a vertex shader");
    if (s.geometryShader) {
        plan->gs = shader(s.geometryShader, call, "geometryShader");
        if (!plan->gs) return false;
        if (plan->gs->blob->stage != ShaderStage::Geometry)
            return fail(call, "geometryShader: " + detail::describe(*plan->gs) + " is not a geometry shader");
    }
    if (s.fragmentShader) {
        plan->fs = shader(s.fragmentShader, call, "fragmentShader");
        if (!plan->fs) return false;
        if (plan->fs->blob->stage != ShaderStage::Fragment)
            return fail(call, "fragmentShader: " + detail::describe(*plan->fs) + " is not a fragment shader");
    }
    std::string log;
    plan->program = programs_.get(gl, plan->vs, plan->gs, plan->fs, &log);
    if (!plan->program) return fail(call, "linking the program of these shaders failed:\n" + log);

    Declared declared;
    for (ShaderRecord* sh : {plan->vs, plan->gs, plan->fs})
        if (sh && !declare(call, *sh, &declared)) return false;
    if (!resolveBindings(call, s.bindings, declared, 0, &plan->bindings)) return false;

    // Vertex input: every input the vertex shader reads must be fed, with matching integer-ness.
    const ShaderReflection& vr = plan->vs->blob->reflection;
    for (uint32_t i = 0; i < vr.vertexInputCount; ++i) {
        const ReflectedVertexInput& in = vr.vertexInputs[i];
        const VertexInput* v = std::find_if(s.vertexInputs.begin(), s.vertexInputs.end(),
                                            [&](const VertexInput& x) { return x.location == in.location; });
        if (v == s.vertexInputs.end())
            return fail(call, "missing vertex input: " + detail::describe(*plan->vs) + " reads '" + in.name +
                                  "' at location " + std::to_string(in.location));
        const bool intInput = v->format == VertexFormat::UInt1;
        if (intInput != (in.scalar == ResourceScalar::Uint || in.scalar == ResourceScalar::Sint))
            return fail(call, "vertexInputs location " + std::to_string(in.location) + ": integer/float mismatch with '" +
                                  in.name + "'");
    }
    uint32_t locations = 0;
    for (size_t i = 0; i < s.vertexInputs.size(); ++i) {
        const VertexInput& v = s.vertexInputs[i];
        const std::string field = "vertexInputs[" + std::to_string(i) + "]";
        if (v.location >= 16) return fail(call, field + ": location " + std::to_string(v.location) + " exceeds 15");
        if (locations & (1u << v.location)) return fail(call, field + ": location " + std::to_string(v.location) + " given twice");
        locations |= 1u << v.location;
        if (v.bufferIndex >= s.vertexBuffers.size())
            return fail(call, field + ".bufferIndex " + std::to_string(v.bufferIndex) + " has no vertexBuffers entry");
        if (v.offset > 2047) return fail(call, field + ".offset " + std::to_string(v.offset) + " exceeds 2047");
        if (uint32_t(v.format) > uint32_t(VertexFormat::Half4)) return fail(call, field + ".format: not a vertex format");
    }
    for (size_t i = 0; i < s.vertexBuffers.size(); ++i) {
        const VertexBufferBinding& vb = s.vertexBuffers[i];
        const std::string field = "vertexBuffers[" + std::to_string(i) + "]";
        BufferRecord* b = buffer(vb.buffer, call, field + ".buffer");
        if (!b) return false;
        if (!(b->desc.usage & BufferUsage::Vertex)) return fail(call, field + ": " + detail::describe(*b) + " lacks BufferUsage::Vertex");
        if (vb.offset >= b->desc.size) return fail(call, field + ": offset beyond the end of " + detail::describe(*b));
        if (vb.stride == 0 || vb.stride > 2048) return fail(call, field + ": stride " + std::to_string(vb.stride) + " not in 1..2048");
        plan->vertexBuffers[i] = b;
        barriers_.require(&plan->bindings.barriers, b->lastShaderWrite, GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    }
    if (kind == DrawKind::Indexed || kind == DrawKind::IndirectIndexed) {
        const IndexBufferBinding& ib = s.indexBuffer;
        BufferRecord* b = buffer(ib.buffer, call, "indexBuffer.buffer");
        if (!b) return false;
        if (!(b->desc.usage & BufferUsage::Index)) return fail(call, "indexBuffer: " + detail::describe(*b) + " lacks BufferUsage::Index");
        if (ib.format != IndexFormat::U16 && ib.format != IndexFormat::U32) return fail(call, "indexBuffer.format: not an index format");
        if (ib.offset % indexBytes(ib.format) || ib.offset >= b->desc.size)
            return fail(call, "indexBuffer.offset " + std::to_string(ib.offset) + " is misaligned or beyond the end of " +
                                  detail::describe(*b));
        plan->indexBuffer = b;
        barriers_.require(&plan->bindings.barriers, b->lastShaderWrite,
                          kind == DrawKind::IndirectIndexed && ib.offset ? GL_BUFFER_UPDATE_BARRIER_BIT
                                                                         : GL_ELEMENT_ARRAY_BARRIER_BIT);
    }
    if (uint32_t(s.topology) > uint32_t(PrimitiveTopology::PointList)) return fail(call, "topology: not a topology");
    if (!prepareTargets(call, s, plan)) return false;
    plan->vao = vertexArrays_.get(gl, s);
    return true;
}

void Device::clearTargets(const DrawCallState& s, const DrawPlan& plan) {
    // Clears obey the scissor, masks and sRGB switch: set them for a whole-target clear first.
    gl.Disable(GL_SCISSOR_TEST);
    gl.Disable(GL_RASTERIZER_DISCARD);
    if (plan.srgb) gl.Enable(GL_FRAMEBUFFER_SRGB);  // a linear clear colour is encoded, as Vulkan does
    else gl.Disable(GL_FRAMEBUFFER_SRGB);
    GLenum invalidate[kMaxColorTargets + 1];
    GLsizei invalidateCount = 0;
    for (uint32_t i = 0; i < s.colorTargets.size(); ++i) {
        const ColorTarget& c = s.colorTargets[i];
        if (c.load == LoadOp::DontCare) invalidate[invalidateCount++] = GL_COLOR_ATTACHMENT0 + i;
        if (c.load != LoadOp::Clear) continue;
        gl.ColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        const Format f = c.view.format == Format::Unknown ? textures_.at(c.view.texture.id).desc.format : c.view.format;
        const auto kind = formatInfo(f).kind;
        // Integer targets take the clear colour converted to integers (5.0f -> 5), clamped to the type.
        if (kind == FormatInfo::Kind::Uint) {
            GLuint u[4];
            for (int k = 0; k < 4; ++k) u[k] = GLuint(std::fmin(std::fmax(c.clearColor[k], 0.0f), 4294967040.0f));
            gl.ClearNamedFramebufferuiv(plan.fbo, GL_COLOR, GLint(i), u);
        } else if (kind == FormatInfo::Kind::Sint) {
            GLint v[4];
            for (int k = 0; k < 4; ++k) v[k] = GLint(std::fmin(std::fmax(c.clearColor[k], -2147483648.0f), 2147483520.0f));
            gl.ClearNamedFramebufferiv(plan.fbo, GL_COLOR, GLint(i), v);
        } else {
            gl.ClearNamedFramebufferfv(plan.fbo, GL_COLOR, GLint(i), c.clearColor);
        }
    }
    if (s.depthTarget.view.texture) {
        if (s.depthTarget.load == LoadOp::Clear) {
            gl.DepthMask(GL_TRUE);
            gl.ClearNamedFramebufferfv(plan.fbo, GL_DEPTH, 0, &s.depthTarget.clearDepth);
        } else if (s.depthTarget.load == LoadOp::DontCare) {
            invalidate[invalidateCount++] = GL_DEPTH_ATTACHMENT;
        }
    }
    if (invalidateCount) gl.InvalidateNamedFramebufferData(plan.fbo, invalidateCount, invalidate);
}

bool Device::drawImpl(const Call& call, const DrawCallState& s, DrawKind kind, const void* args, BufferHandle argsHandle,
                      uint64_t argsOffset) {
    makeCurrent();
    DrawPlan plan;
    if (!prepareDraw(call, s, kind, &plan)) return false;

    // Direct draws: check that the vertices, instances and indices read stay inside their buffers.
    auto checkFetch = [&](uint32_t first, uint32_t count, bool perInstance) {
        if (!count) return true;
        for (const VertexInput& in : s.vertexInputs) {
            const VertexBufferBinding& vb = s.vertexBuffers[in.bufferIndex];
            if (vb.perInstance != perInstance) continue;
            const auto end = rhi::sizes::fetchEnd(vb.offset + in.offset, first, count, vb.stride, rhi::sizes::vertexFormatBytes(in.format));
            if (!end || *end > plan.vertexBuffers[in.bufferIndex]->desc.size)
                return fail(call, std::string(perInstance ? "instances " : "vertices ") + std::to_string(first) + ".." +
                                      std::to_string(uint64_t(first) + count - 1) + " read past the end of vertexBuffers[" +
                                      std::to_string(in.bufferIndex) + "] " + detail::describe(*plan.vertexBuffers[in.bufferIndex]));
        }
        return true;
    };
    BufferRecord* argsBuffer = nullptr;
    if (kind == DrawKind::Direct) {
        const auto& a = *static_cast<const DrawArgs*>(args);
        if (!checkFetch(a.firstVertex, a.vertexCount, false) || !checkFetch(a.firstInstance, a.instanceCount, true)) return false;
    } else if (kind == DrawKind::Indexed) {
        const auto& a = *static_cast<const DrawIndexedArgs*>(args);
        const uint64_t end = s.indexBuffer.offset + (uint64_t(a.firstIndex) + a.indexCount) * indexBytes(s.indexBuffer.format);
        if (end > plan.indexBuffer->desc.size)
            return fail(call, "indices " + std::to_string(a.firstIndex) + "+" + std::to_string(a.indexCount) +
                                  " read past the end of " + detail::describe(*plan.indexBuffer));
        if (!checkFetch(a.firstInstance, a.instanceCount, true)) return false;
    } else {
        argsBuffer = buffer(argsHandle, call, "args");
        if (!argsBuffer) return false;
        const uint64_t bytes = kind == DrawKind::IndirectIndexed ? sizeof(DrawIndexedArgs) : sizeof(DrawArgs);
        if (!(argsBuffer->desc.usage & BufferUsage::IndirectArgs))
            return fail(call, "args: " + detail::describe(*argsBuffer) + " was not created with BufferUsage::IndirectArgs");
        if (argsOffset % 4) return fail(call, "offset " + std::to_string(argsOffset) + " is not a multiple of 4");
        if (argsOffset > argsBuffer->desc.size || argsBuffer->desc.size - argsOffset < bytes)
            return fail(call, "args: " + std::to_string(bytes) + " bytes at offset " + std::to_string(argsOffset) +
                                  " exceed the " + std::to_string(argsBuffer->desc.size) + " bytes of " + detail::describe(*argsBuffer));
        barriers_.require(&plan.bindings.barriers, argsBuffer->lastShaderWrite, GL_COMMAND_BARRIER_BIT);
    }

    barriers_.issue(gl, plan.bindings.barriers);
    pushLabel(s.label);
    // GL's indirect indexed draw has no index-buffer byte offset (firstIndex counts from the buffer's
    // start), so an offset index buffer is copied to a scratch buffer first.
    GLuint elementBuffer = plan.indexBuffer ? plan.indexBuffer->name : 0;
    uint64_t indexOffset = s.indexBuffer.offset;
    if (kind == DrawKind::IndirectIndexed && s.indexBuffer.offset) {
        const uint64_t size = plan.indexBuffer->desc.size - s.indexBuffer.offset;
        if (size > scratchIndexSize_) {
            if (scratchIndexBuffer_) gl.DeleteBuffers(1, &scratchIndexBuffer_);
            gl.CreateBuffers(1, &scratchIndexBuffer_);
            gl.NamedBufferStorage(scratchIndexBuffer_, GLsizeiptr(size), nullptr, 0);
            scratchIndexSize_ = size;
        }
        gl.CopyNamedBufferSubData(plan.indexBuffer->name, scratchIndexBuffer_, GLintptr(s.indexBuffer.offset), 0, GLsizeiptr(size));
        elementBuffer = scratchIndexBuffer_;
        indexOffset = 0;
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, plan.fbo);
    clearTargets(s, plan);
    uint32_t clipDistances = plan.gs ? plan.gs->clipDistances : plan.vs->clipDistances;
    applyDrawState(gl, s, plan.width, plan.height, clipDistances, plan.srgb);
    gl.UseProgram(plan.program);
    gl.BindVertexArray(plan.vao);
    for (uint32_t i = 0; i < s.vertexBuffers.size(); ++i)
        gl.VertexArrayVertexBuffer(plan.vao, i, plan.vertexBuffers[i]->name, GLintptr(s.vertexBuffers[i].offset),
                                   GLsizei(s.vertexBuffers[i].stride));
    gl.VertexArrayElementBuffer(plan.vao, elementBuffer);
    applyBindings(plan.bindings);

    const GLenum mode = topologyMode(s.topology);
    const GLenum type = indexType(s.indexBuffer.format);
    const uint32_t isz = indexBytes(s.indexBuffer.format);
    switch (kind) {
        case DrawKind::Direct: {
            const auto& a = *static_cast<const DrawArgs*>(args);
            gl.DrawArraysInstancedBaseInstance(mode, GLint(a.firstVertex), GLsizei(a.vertexCount), GLsizei(a.instanceCount),
                                               a.firstInstance);
            break;
        }
        case DrawKind::Indexed: {
            const auto& a = *static_cast<const DrawIndexedArgs*>(args);
            const auto* first = reinterpret_cast<const void*>(uintptr_t(indexOffset + uint64_t(a.firstIndex) * isz));
            gl.DrawElementsInstancedBaseVertexBaseInstance(mode, GLsizei(a.indexCount), type, first, GLsizei(a.instanceCount),
                                                           a.vertexOffset, a.firstInstance);
            break;
        }
        case DrawKind::Indirect:
        case DrawKind::IndirectIndexed:
            gl.BindBuffer(GL_DRAW_INDIRECT_BUFFER, argsBuffer->name);
            if (kind == DrawKind::Indirect) gl.DrawArraysIndirect(mode, reinterpret_cast<const void*>(uintptr_t(argsOffset)));
            else gl.DrawElementsIndirect(mode, type, reinterpret_cast<const void*>(uintptr_t(argsOffset)));
            gl.BindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
            break;
    }
    finishBindings(plan.bindings);
    // Our cached VAO keeps no reference to the app's buffers between calls.
    for (uint32_t i = 0; i < s.vertexBuffers.size(); ++i) gl.VertexArrayVertexBuffer(plan.vao, i, 0, 0, 0);
    gl.VertexArrayElementBuffer(plan.vao, 0);
    gl.BindVertexArray(0);
    gl.UseProgram(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    popLabel(s.label);
    return true;
}

bool Device::draw(const DrawCallState& state, const DrawArgs& args) {
    return drawImpl(Call{"draw", state.label}, state, DrawKind::Direct, &args, {}, 0);
}

bool Device::drawIndexed(const DrawCallState& state, const DrawIndexedArgs& args) {
    return drawImpl(Call{"drawIndexed", state.label}, state, DrawKind::Indexed, &args, {}, 0);
}

bool Device::drawIndirect(const DrawCallState& state, BufferHandle args, uint64_t offset, bool indexed) {
    return drawImpl(Call{"drawIndirect", state.label}, state, indexed ? DrawKind::IndirectIndexed : DrawKind::Indirect,
                    nullptr, args, offset);
}

}  // namespace bricklight::gl::detail
