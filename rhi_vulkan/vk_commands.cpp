// dispatch / dispatchIndirect / draw / drawIndexed / drawIndirect: check everything, then record
// barriers, pipeline, descriptors and the command. Draws use dynamic rendering, one render pass instance
// per draw (the record is complete; nothing is kept open between calls).
#include <algorithm>
#include <cmath>

#include "../rhi/size_math.h"
#include "vk_device.h"
#include "vk_formats.h"

namespace bricklight::vulkan::detail {

void VulkanDevice::beginCallLabel(VkCommandBuffer c, const char* label) {
    if (!debugUtils_ || !label || !*label) return;
    VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    l.pLabelName = label;
    beginLabel_(c, &l);
}
void VulkanDevice::endCallLabel(VkCommandBuffer c, const char* label) {
    if (debugUtils_ && label && *label) endLabel_(c);
}

bool VulkanDevice::prepareDispatch(const rhi::DispatchState& state, const std::string& call, CallPlan& plan,
                                   Shader** shader, const Program** program, VkPipeline* pipeline) {
    Shader* s = findShader(state.shader, call, "shader");
    if (!s) return false;
    if (s->blob->stage != rhi::ShaderStage::Compute) return fail(call + ": shader '" + s->name + "' is not a compute shader");
    const Program* p = getProgram({s}, call);
    if (!p || !planBindings(*p, state.bindings, state.flags, call, plan)) return false;
    VkPipeline pipe = getComputePipeline(*p, *s, call);
    if (!pipe) return false;
    *shader = s, *program = p, *pipeline = pipe;
    return true;
}

bool VulkanDevice::dispatch(const rhi::DispatchState& state, uint32_t x, uint32_t y, uint32_t z) {
    const std::string call = "dispatch" + quoted(state.label);
    const uint32_t* max = caps_.limits.maxComputeGroupCount;
    if (x > max[0] || y > max[1] || z > max[2])
        return fail(call + ": group count " + std::to_string(x) + "x" + std::to_string(y) + "x" + std::to_string(z) +
                    " exceeds maxComputeGroupCount");
    CallPlan plan;
    Shader* shader;
    const Program* program;
    VkPipeline pipeline;
    if (!prepareDispatch(state, call, plan, &shader, &program, &pipeline)) return false;
    if (!x || !y || !z) return true;  // an empty dispatch does nothing
    VkCommandBuffer c = cmd();
    beginCallLabel(c, state.label);
    recordBarriers(c, plan);
    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    bool ok = bindDescriptors(c, VK_PIPELINE_BIND_POINT_COMPUTE, *program, plan);
    if (ok) vkCmdDispatch(c, x, y, z);
    endCallLabel(c, state.label);
    releaseWrapped(c, plan);
    return ok;
}

bool VulkanDevice::dispatchIndirect(const rhi::DispatchState& state, rhi::BufferHandle args, uint64_t offset) {
    const std::string call = "dispatchIndirect" + quoted(state.label);
    CallPlan plan;
    Shader* shader;
    const Program* program;
    VkPipeline pipeline;
    if (!prepareDispatch(state, call, plan, &shader, &program, &pipeline)) return false;
    Buffer* a = findBuffer(args, call, "args");
    if (!a) return false;
    if (!(a->desc.usage & rhi::BufferUsage::IndirectArgs))
        return fail(call + ": args " + bufferName(*a) + " was created without IndirectArgs usage");
    if (offset % 4 || !rhi::sizes::rangeInside(offset, sizeof(rhi::DispatchIndirectArgs), a->desc.size))
        return fail(call + ": args offset " + std::to_string(offset) + " is unaligned or leaves fewer than 12 bytes in " +
                    bufferName(*a));
    AccessRequest req;
    req.stages = VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
    req.access = VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT;
    req.shaderWriteOnly = false;
    addBufferUse(plan, *a, req);
    VkCommandBuffer c = cmd();
    beginCallLabel(c, state.label);
    recordBarriers(c, plan);
    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    bool ok = bindDescriptors(c, VK_PIPELINE_BIND_POINT_COMPUTE, *program, plan);
    if (ok) vkCmdDispatchIndirect(c, a->buffer, offset);
    endCallLabel(c, state.label);
    releaseWrapped(c, plan);
    return ok;
}

// The viewport and depth bias as Vulkan accepts them (VkViewport's rules), checked here rather than left to
// the validation layer: a NaN reached the scissor's float-to-int clamp, and any other value outside them is
// undefined behaviour in the driver.
bool VulkanDevice::checkViewport(const rhi::DrawCallState& s, const std::string& call) {
    const rhi::Viewport& v = s.viewport;
    const VkPhysicalDeviceLimits& l = props_.limits;
    if (!std::isfinite(s.raster.depthBiasConstant) || !std::isfinite(s.raster.depthBiasSlope))
        return fail(call + ": raster.depthBiasConstant and depthBiasSlope must be finite");
    if (!(v.minDepth >= 0.0f && v.minDepth <= 1.0f && v.maxDepth >= 0.0f && v.maxDepth <= 1.0f))
        return fail(call + ": viewport.minDepth and maxDepth must be in [0, 1]");
    if (v.width == 0.0f) return true;  // the whole target: x, y and height are not used
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.width) || !std::isfinite(v.height))
        return fail(call + ": viewport: x, y, width and height must be finite");
    if (!(v.width > 0.0f && v.height > 0.0f && v.width <= float(l.maxViewportDimensions[0]) &&
          v.height <= float(l.maxViewportDimensions[1])))
        return fail(call + ": viewport " + std::to_string(v.width) + "x" + std::to_string(v.height) +
                    " must be positive and within maxViewportDimensions");
    if (!(v.x >= l.viewportBoundsRange[0] && v.y >= l.viewportBoundsRange[0] && v.x + v.width <= l.viewportBoundsRange[1] &&
          v.y + v.height <= l.viewportBoundsRange[1]))
        return fail(call + ": viewport (" + std::to_string(v.x) + ", " + std::to_string(v.y) +
                    ") lies outside viewportBoundsRange");
    return true;
}

bool VulkanDevice::prepareDraw(const rhi::DrawCallState& s, const std::string& call, CallPlan& plan,
                               const Program** program, VkPipeline* pipeline, VkExtent2D* extent) {
    namespace TU = rhi::TextureUsage;
    Shader* vs = findShader(s.vertexShader, call, "vertexShader");
    if (!vs) return false;
    if (vs->blob->stage != rhi::ShaderStage::Vertex) return fail(call + ": vertexShader '" + vs->name + "' is not a vertex shader");
    Shader* gs = nullptr;
    Shader* fs = nullptr;
    if (s.geometryShader) {
        if (!(gs = findShader(s.geometryShader, call, "geometryShader"))) return false;
        if (gs->blob->stage != rhi::ShaderStage::Geometry)
            return fail(call + ": geometryShader '" + gs->name + "' is not a geometry shader");
    }
    if (s.fragmentShader) {
        if (!(fs = findShader(s.fragmentShader, call, "fragmentShader"))) return false;
        if (fs->blob->stage != rhi::ShaderStage::Fragment)
            return fail(call + ": fragmentShader '" + fs->name + "' is not a fragment shader");
    }
    if (s.colorTargets.empty() && !s.depthTarget.view.texture)
        return fail(call + ": a draw needs at least one colour or depth target");
    if (s.colorTargets.size() > caps_.limits.maxColorTargets)
        return fail(call + ": " + std::to_string(s.colorTargets.size()) + " colour targets exceed maxColorTargets");
    if (s.raster.depthClamp && !enabled_.depthClamp) return fail(call + ": raster.depthClamp is not supported on this device");
    if (!checkViewport(s, call)) return false;

    // Targets: one mip and one layer each, all the same size.
    extent->width = extent->height = 0;
    auto checkTarget = [&](const rhi::TextureView& view, const std::string& where, bool depth, const AccessRequest& req) {
        Texture* t = findTexture(view.texture, where, "texture");
        if (!t) return false;
        const std::string tname = textureName(*t);
        if (!(t->desc.usage & (depth ? TU::DepthTarget : TU::RenderTarget)))
            return fail(where + ": " + tname + " was created without " + (depth ? "DepthTarget" : "RenderTarget") + " usage");
        rhi::Format fmt = view.format == rhi::Format::Unknown ? t->desc.format : view.format;
        if (!viewFormatCompatible(t->desc.format, fmt))
            return fail(where + ": view format " + rhi::formatName(fmt) + " cannot reinterpret " + tname);
        if (!caps_.supports(fmt, depth ? rhi::FormatSupport::DepthTarget : rhi::FormatSupport::RenderTarget))
            return fail(where + ": format " + rhi::formatName(fmt) + " cannot be a " + (depth ? "depth" : "colour") +
                        " target on this device");
        if (view.baseMip >= t->desc.mipLevels)
            return fail(where + ": baseMip " + std::to_string(view.baseMip) + " is outside " + tname);
        const bool is3D = t->desc.dimension == rhi::TextureDimension::Texture3D;
        const uint32_t layers = is3D ? rhi::textureDepth(t->desc, view.baseMip) : t->layers;
        if (view.baseLayer >= layers)
            return fail(where + ": baseLayer " + std::to_string(view.baseLayer) + " is outside " + tname);
        const uint32_t w = rhi::mipExtent(t->desc.width, view.baseMip), h = rhi::mipExtent(t->desc.height, view.baseMip);
        if (extent->width && (extent->width != w || extent->height != h))
            return fail(where + ": " + tname + " mip " + std::to_string(view.baseMip) + " is " + std::to_string(w) + "x" +
                        std::to_string(h) + " but an earlier target is " + std::to_string(extent->width) + "x" +
                        std::to_string(extent->height));
        extent->width = w, extent->height = h;
        return addTextureUse(plan, *t, view.baseMip, 1, is3D ? 0 : view.baseLayer, 1, req, where, "target");
    };
    for (size_t i = 0; i < s.colorTargets.size(); ++i) {
        const rhi::ColorTarget& ct = s.colorTargets[i];
        const std::string where = call + ": colorTargets[" + std::to_string(i) + "]";
        AccessRequest req;
        req.stages = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        req.access = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
        if (ct.load == rhi::LoadOp::Load || ct.blend.enable) req.access |= VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT;
        req.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        req.write = true;
        req.shaderWriteOnly = false;
        if (!checkTarget(ct.view, where, false, req)) return false;
        const rhi::TextureDesc* d = describe(ct.view.texture);
        rhi::Format fmt = ct.view.format == rhi::Format::Unknown ? d->format : ct.view.format;
        if (ct.blend.enable && !caps_.supports(fmt, rhi::FormatSupport::Blendable))
            return fail(where + ": format " + rhi::formatName(fmt) + " does not support blending");
        if (i > 0 && !enabled_.independentBlend) {
            const auto& a = s.colorTargets[0].blend;
            const auto& b = ct.blend;
            if (a.enable != b.enable || a.srcColor != b.srcColor || a.dstColor != b.dstColor || a.colorOp != b.colorOp ||
                a.srcAlpha != b.srcAlpha || a.dstAlpha != b.dstAlpha || a.alphaOp != b.alphaOp || a.writeMask != b.writeMask)
                return fail(where + ": per-target blend state differs from target 0 (independentBlend unsupported)");
        }
    }
    if (s.depthTarget.view.texture) {
        const std::string where = call + ": depthTarget";
        AccessRequest req;
        req.stages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
        req.write = s.depth.writeEnable || s.depthTarget.load != rhi::LoadOp::Load;
        if (s.depthTarget.load == rhi::LoadOp::Load || s.depth.testEnable)
            req.access |= VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
        if (req.write) req.access |= VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
        req.layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        req.shaderWriteOnly = false;
        if (!checkTarget(s.depthTarget.view, where, true, req)) return false;
    }

    // Vertex input.
    for (size_t i = 0; i < s.vertexBuffers.size(); ++i) {
        const std::string where = call + ": vertexBuffers[" + std::to_string(i) + "]";
        Buffer* b = findBuffer(s.vertexBuffers[i].buffer, where, "buffer");
        if (!b) return false;
        if (!(b->desc.usage & rhi::BufferUsage::Vertex))
            return fail(where + ": " + bufferName(*b) + " was created without Vertex usage");
        if (s.vertexBuffers[i].offset >= b->desc.size)
            return fail(where + ": offset " + std::to_string(s.vertexBuffers[i].offset) + " is outside " + bufferName(*b));
        if (s.vertexBuffers[i].stride > props_.limits.maxVertexInputBindingStride)
            return fail(where + ": stride exceeds maxVertexInputBindingStride");
        AccessRequest req;
        req.stages = VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT;
        req.access = VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT;
        req.shaderWriteOnly = false;
        addBufferUse(plan, *b, req);
    }
    for (size_t i = 0; i < s.vertexInputs.size(); ++i) {
        const auto& in = s.vertexInputs[i];
        if (in.bufferIndex >= s.vertexBuffers.size())
            return fail(call + ": vertexInputs[" + std::to_string(i) + "]: bufferIndex " + std::to_string(in.bufferIndex) +
                        " has no vertex buffer");
        for (size_t j = 0; j < i; ++j)
            if (s.vertexInputs[j].location == in.location)
                return fail(call + ": vertexInputs[" + std::to_string(i) + "]: location " + std::to_string(in.location) +
                            " is given twice");
    }
    const rhi::ShaderReflection& vr = vs->blob->reflection;
    for (uint32_t i = 0; i < vr.vertexInputCount; ++i) {
        const auto& need = vr.vertexInputs[i];
        const rhi::VertexInput* in = nullptr;
        for (const auto& v : s.vertexInputs)
            if (v.location == need.location) in = &v;
        if (!in)
            return fail(call + ": vertex shader '" + vs->name + "' reads location " + std::to_string(need.location) + " ('" +
                        need.name + "') but vertexInputs has none");
        if (vertexFormatScalar(in->format) != need.scalar)
            return fail(call + ": vertex input location " + std::to_string(need.location) + ": format " +
                        vertexFormatName(in->format) + " does not match the shader's '" + need.name + "'");
    }

    const Program* p = getProgram(fs && gs ? std::vector<Shader*>{vs, gs, fs}
                                  : fs     ? std::vector<Shader*>{vs, fs}
                                  : gs     ? std::vector<Shader*>{vs, gs}
                                           : std::vector<Shader*>{vs},
                                  call);
    if (!p || !planBindings(*p, s.bindings, 0, call, plan)) return false;
    VkPipeline pipe = getGraphicsPipeline(*p, s, vs, gs, fs, call);
    if (!pipe) return false;
    *program = p, *pipeline = pipe;
    return true;
}

void VulkanDevice::recordDraw(const rhi::DrawCallState& s, const Program& program, VkPipeline pipeline, VkExtent2D extent,
                              CallPlan& plan, const std::function<void(VkCommandBuffer)>& issue) {
    VkCommandBuffer c = cmd();
    beginCallLabel(c, s.label);
    recordBarriers(c, plan);
    vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    if (!bindDescriptors(c, VK_PIPELINE_BIND_POINT_GRAPHICS, program, plan)) {
        endCallLabel(c, s.label);
        return;
    }
    VkRenderingAttachmentInfo colors[rhi::kMaxColorTargets];
    for (size_t i = 0; i < s.colorTargets.size(); ++i) {
        const rhi::ColorTarget& ct = s.colorTargets[i];
        Texture& t = *textures_[ct.view.texture.id];
        rhi::Format fmt = ct.view.format == rhi::Format::Unknown ? t.desc.format : ct.view.format;
        const bool is3D = t.desc.dimension == rhi::TextureDimension::Texture3D;
        ViewKey key{toVkFormat(fmt), VK_IMAGE_VIEW_TYPE_2D, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, ct.view.baseMip, 1,
                    ct.view.baseLayer, 1};
        (void)is3D;  // a 2D view of a 3D slice: baseLayer names the slice (2D_ARRAY_COMPATIBLE image)
        VkRenderingAttachmentInfo& a = colors[i];
        a = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = getView(t, key);
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = ct.load == rhi::LoadOp::Clear  ? VK_ATTACHMENT_LOAD_OP_CLEAR
                   : ct.load == rhi::LoadOp::Load ? VK_ATTACHMENT_LOAD_OP_LOAD
                                                  : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        // Integer targets take the clear colour's values converted to integers.
        switch (formatScalar(fmt)) {
            case rhi::ResourceScalar::Uint:
                for (int k = 0; k < 4; ++k) a.clearValue.color.uint32[k] = static_cast<uint32_t>(ct.clearColor[k]);
                break;
            case rhi::ResourceScalar::Sint:
                for (int k = 0; k < 4; ++k) a.clearValue.color.int32[k] = static_cast<int32_t>(ct.clearColor[k]);
                break;
            default:
                for (int k = 0; k < 4; ++k) a.clearValue.color.float32[k] = ct.clearColor[k];
        }
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    if (s.depthTarget.view.texture) {
        Texture& t = *textures_[s.depthTarget.view.texture.id];
        ViewKey key{t.format, VK_IMAGE_VIEW_TYPE_2D, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, s.depthTarget.view.baseMip,
                    1, s.depthTarget.view.baseLayer, 1};
        depth.imageView = getView(t, key);
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        depth.loadOp = s.depthTarget.load == rhi::LoadOp::Clear  ? VK_ATTACHMENT_LOAD_OP_CLEAR
                       : s.depthTarget.load == rhi::LoadOp::Load ? VK_ATTACHMENT_LOAD_OP_LOAD
                                                                 : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        // A read-only depth target is not stored (STORE_OP_NONE), so read-only draws do not write it.
        const bool writes = s.depth.writeEnable || s.depthTarget.load != rhi::LoadOp::Load;
        depth.storeOp = writes ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_NONE;
        depth.clearValue.depthStencil.depth = s.depthTarget.clearDepth;
    }
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, extent};
    ri.layerCount = 1;
    ri.colorAttachmentCount = static_cast<uint32_t>(s.colorTargets.size());
    ri.pColorAttachments = colors;
    ri.pDepthAttachment = s.depthTarget.view.texture ? &depth : nullptr;
    vkCmdBeginRendering(c, &ri);

    // Viewport: width 0 = the whole target. Not flipped: memory row 0 is clip-space y = -1.
    VkViewport vp{s.viewport.x, s.viewport.y, s.viewport.width, s.viewport.height, s.viewport.minDepth, s.viewport.maxDepth};
    if (s.viewport.width == 0.0f) vp.x = 0, vp.y = 0, vp.width = float(extent.width), vp.height = float(extent.height);
    vkCmdSetViewport(c, 0, 1, &vp);
    // Scissor: width 0 = the viewport; always clipped to the target.
    float sx0 = vp.x, sy0 = vp.y, sx1 = vp.x + vp.width, sy1 = vp.y + vp.height;
    if (s.scissor.width != 0) {
        sx0 = float(s.scissor.x), sy0 = float(s.scissor.y);
        sx1 = sx0 + float(s.scissor.width), sy1 = sy0 + float(s.scissor.height);
    }
    auto clampTo = [](float v, uint32_t hi) { return static_cast<int32_t>(std::clamp(v, 0.0f, float(hi))); };
    int32_t x0 = clampTo(std::floor(sx0), extent.width), y0 = clampTo(std::floor(sy0), extent.height);
    int32_t x1 = clampTo(std::ceil(sx1), extent.width), y1 = clampTo(std::ceil(sy1), extent.height);
    VkRect2D scissor{{x0, y0}, {uint32_t(std::max(0, x1 - x0)), uint32_t(std::max(0, y1 - y0))}};
    vkCmdSetScissor(c, 0, 1, &scissor);

    for (uint32_t i = 0; i < s.vertexBuffers.size(); ++i) {
        VkBuffer b = buffers_[s.vertexBuffers[i].buffer.id]->buffer;
        VkDeviceSize offset = s.vertexBuffers[i].offset;
        vkCmdBindVertexBuffers(c, i, 1, &b, &offset);
    }
    issue(c);
    vkCmdEndRendering(c);
    endCallLabel(c, s.label);
    releaseWrapped(c, plan);
}

bool VulkanDevice::draw(const rhi::DrawCallState& state, const rhi::DrawArgs& args) {
    const std::string call = "draw" + quoted(state.label);
    CallPlan plan;
    const Program* program;
    VkPipeline pipeline;
    VkExtent2D extent;
    if (!prepareDraw(state, call, plan, &program, &pipeline, &extent)) return false;
    recordDraw(state, *program, pipeline, extent, plan, [&](VkCommandBuffer c) {
        vkCmdDraw(c, args.vertexCount, args.instanceCount, args.firstVertex, args.firstInstance);
    });
    return true;
}

namespace {
uint32_t indexBytes(rhi::IndexFormat f) { return f == rhi::IndexFormat::U16 ? 2 : 4; }
}  // namespace

bool VulkanDevice::drawIndexed(const rhi::DrawCallState& state, const rhi::DrawIndexedArgs& args) {
    const std::string call = "drawIndexed" + quoted(state.label);
    CallPlan plan;
    const Program* program;
    VkPipeline pipeline;
    VkExtent2D extent;
    if (!prepareDraw(state, call, plan, &program, &pipeline, &extent)) return false;
    const auto& ib = state.indexBuffer;
    Buffer* b = findBuffer(ib.buffer, call, "indexBuffer");
    if (!b) return false;
    if (!(b->desc.usage & rhi::BufferUsage::Index))
        return fail(call + ": indexBuffer " + bufferName(*b) + " was created without Index usage");
    if (ib.offset % indexBytes(ib.format) || ib.offset >= b->desc.size)
        return fail(call + ": indexBuffer offset " + std::to_string(ib.offset) + " is unaligned or outside " +
                    bufferName(*b));
    AccessRequest req;
    req.stages = VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT;
    req.access = VK_ACCESS_2_INDEX_READ_BIT;
    req.shaderWriteOnly = false;
    addBufferUse(plan, *b, req);
    recordDraw(state, *program, pipeline, extent, plan, [&](VkCommandBuffer c) {
        vkCmdBindIndexBuffer(c, b->buffer, ib.offset,
                             ib.format == rhi::IndexFormat::U16 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(c, args.indexCount, args.instanceCount, args.firstIndex, args.vertexOffset, args.firstInstance);
    });
    return true;
}

bool VulkanDevice::drawIndirect(const rhi::DrawCallState& state, rhi::BufferHandle args, uint64_t offset, bool indexed) {
    const std::string call = "drawIndirect" + quoted(state.label);
    CallPlan plan;
    const Program* program;
    VkPipeline pipeline;
    VkExtent2D extent;
    if (!prepareDraw(state, call, plan, &program, &pipeline, &extent)) return false;
    Buffer* a = findBuffer(args, call, "args");
    if (!a) return false;
    if (!(a->desc.usage & rhi::BufferUsage::IndirectArgs))
        return fail(call + ": args " + bufferName(*a) + " was created without IndirectArgs usage");
    const uint64_t need = indexed ? sizeof(rhi::DrawIndexedArgs) : sizeof(rhi::DrawArgs);
    if (offset % 4 || !rhi::sizes::rangeInside(offset, need, a->desc.size))
        return fail(call + ": args offset " + std::to_string(offset) + " is unaligned or leaves fewer than " +
                    std::to_string(need) + " bytes in " + bufferName(*a));
    AccessRequest req;
    req.stages = VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
    req.access = VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT;
    req.shaderWriteOnly = false;
    addBufferUse(plan, *a, req);
    Buffer* ib = nullptr;
    if (indexed) {
        const auto& ibs = state.indexBuffer;
        if (!(ib = findBuffer(ibs.buffer, call, "indexBuffer"))) return false;
        if (!(ib->desc.usage & rhi::BufferUsage::Index))
            return fail(call + ": indexBuffer " + bufferName(*ib) + " was created without Index usage");
        if (ibs.offset % indexBytes(ibs.format) || ibs.offset >= ib->desc.size)
            return fail(call + ": indexBuffer offset is unaligned or outside " + bufferName(*ib));
        AccessRequest ireq;
        ireq.stages = VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT;
        ireq.access = VK_ACCESS_2_INDEX_READ_BIT;
        ireq.shaderWriteOnly = false;
        addBufferUse(plan, *ib, ireq);
    }
    recordDraw(state, *program, pipeline, extent, plan, [&](VkCommandBuffer c) {
        if (indexed) {
            vkCmdBindIndexBuffer(c, ib->buffer, state.indexBuffer.offset,
                                 state.indexBuffer.format == rhi::IndexFormat::U16 ? VK_INDEX_TYPE_UINT16
                                                                                   : VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexedIndirect(c, a->buffer, offset, 1, 0);
        } else {
            vkCmdDrawIndirect(c, a->buffer, offset, 1, 0);
        }
    });
    return true;
}

}  // namespace bricklight::vulkan::detail
