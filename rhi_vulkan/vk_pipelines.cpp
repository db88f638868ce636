// Descriptor set layouts and pipeline layouts built from shader reflection, and the pipeline cache.
// One set (0) per call; the layout is the union of the bindings that the call's shaders declare, each
// binding visible to exactly the stages that declare it. Pipelines are cached by a key made of the state
// that defines them (viewport and scissor are dynamic).
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "vk_device.h"
#include "vk_formats.h"

namespace bricklight::vulkan::detail {

namespace {
constexpr uint32_t kClassBase[] = {0, 16, 32, 48, 64};
constexpr VkDescriptorType kClassType[] = {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                           VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                           VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};

void stagesOf(rhi::ShaderStage s, VkShaderStageFlags* shader, VkPipelineStageFlags2* pipeline) {
    switch (s) {
        case rhi::ShaderStage::Compute:
            *shader = VK_SHADER_STAGE_COMPUTE_BIT, *pipeline = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
            return;
        case rhi::ShaderStage::Vertex:
            *shader = VK_SHADER_STAGE_VERTEX_BIT, *pipeline = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
            return;
        case rhi::ShaderStage::Geometry:
            *shader = VK_SHADER_STAGE_GEOMETRY_BIT, *pipeline = VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT;
            return;
        case rhi::ShaderStage::Fragment:
            *shader = VK_SHADER_STAGE_FRAGMENT_BIT, *pipeline = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
            return;
    }
}

// Appends the bytes of plain values to a cache key.
struct KeyWriter {
    std::string key;
    template <typename T>
    void add(const T& v) {
        key.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
};
}  // namespace

const SetLayout* VulkanDevice::getSetLayout(const std::vector<ProgramBinding>& bindings) {
    const bool push = pushDescriptors_ && bindings.size() <= maxPushDescriptors_;
    KeyWriter k;
    k.add(push);
    for (const auto& b : bindings) {
        k.add(b.binding);
        k.add(b.type);
        k.add(b.stages);
    }
    auto it = setLayouts_.find(k.key);
    if (it != setLayouts_.end()) return it->second.get();
    std::vector<VkDescriptorSetLayoutBinding> vkb;
    for (const auto& b : bindings) vkb.push_back({b.binding, b.type, 1, b.stages, nullptr});
    VkDescriptorSetLayoutCreateInfo dci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    dci.flags = push ? VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR : 0;
    dci.bindingCount = static_cast<uint32_t>(vkb.size());
    dci.pBindings = vkb.data();
    auto layout = std::make_unique<SetLayout>();
    layout->push = push;
    if (vkCreateDescriptorSetLayout(device_, &dci, nullptr, &layout->setLayout) != VK_SUCCESS) return nullptr;
    VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pci.setLayoutCount = 1;
    pci.pSetLayouts = &layout->setLayout;
    if (vkCreatePipelineLayout(device_, &pci, nullptr, &layout->pipelineLayout) != VK_SUCCESS) {
        vkDestroyDescriptorSetLayout(device_, layout->setLayout, nullptr);
        return nullptr;
    }
    const SetLayout* raw = layout.get();
    setLayouts_[k.key] = std::move(layout);
    return raw;
}

const Program* VulkanDevice::getProgram(const std::vector<Shader*>& shaders, const std::string& call) {
    std::string key;
    for (Shader* s : shaders) key += std::to_string(s->id) + ",";
    auto it = programs_.find(key);
    if (it != programs_.end()) return it->second.get();
    auto program = std::make_unique<Program>();
    for (Shader* s : shaders) {
        program->shaderIds.push_back(s->id);
        VkShaderStageFlags shaderStage = 0;
        VkPipelineStageFlags2 pipelineStage = 0;
        stagesOf(s->blob->stage, &shaderStage, &pipelineStage);
        const rhi::ShaderReflection& r = s->blob->reflection;
        for (uint32_t i = 0; i < r.bindingCount; ++i) {
            const rhi::ReflectedBinding& rb = r.bindings[i];
            if (rb.bindingClass > static_cast<uint8_t>(rhi::BindingClass::StorageImage))
                return fail(call + ": shader '" + s->name + "' reflects an unknown binding class"), nullptr;
            ProgramBinding b;
            b.cls = static_cast<rhi::BindingClass>(rb.bindingClass);
            b.slot = rb.slot;
            b.binding = kClassBase[rb.bindingClass] + rb.slot;
            b.type = kClassType[rb.bindingClass];
            b.stages = shaderStage;
            b.pipelineStages = pipelineStage;
            b.reflection = &rb;
            auto same = std::find_if(program->bindings.begin(), program->bindings.end(),
                                     [&](const ProgramBinding& o) { return o.binding == b.binding; });
            if (same == program->bindings.end()) {
                program->bindings.push_back(b);
                continue;
            }
            // Declared by several stages: the declarations must agree.
            if (same->reflection->dimension != rb.dimension || same->reflection->imageFormat != rb.imageFormat ||
                same->reflection->scalar != rb.scalar)
                return fail(call + ": " + rhi::bindingClassName(b.cls) + " slot " + std::to_string(b.slot) +
                            " is declared differently by the stages of the draw ('" + s->name + "')"),
                       nullptr;
            same->stages |= shaderStage;
            same->pipelineStages |= pipelineStage;
            // A stage that writes wins: keep the writable declaration for access checks.
            if (same->reflection->readOnly && !rb.readOnly) same->reflection = &rb;
        }
    }
    std::sort(program->bindings.begin(), program->bindings.end(),
              [](const ProgramBinding& a, const ProgramBinding& b) { return a.binding < b.binding; });
    program->layout = getSetLayout(program->bindings);
    if (!program->layout) return fail(call + ": cannot create the descriptor set / pipeline layout"), nullptr;
    const Program* raw = program.get();
    programs_[key] = std::move(program);
    return raw;
}

VkPipeline VulkanDevice::getComputePipeline(const Program& program, Shader& shader, const std::string& call) {
    const std::string key = std::string("c").append(std::to_string(shader.id));
    auto it = pipelines_.find(key);
    if (it != pipelines_.end()) return it->second.pipeline;
    VkComputePipelineCreateInfo cpci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    cpci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    cpci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cpci.stage.module = shader.module;
    cpci.stage.pName = "main";
    cpci.layout = program.layout->pipelineLayout;
    if (executableStatistics_) cpci.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
    VkPipeline pipeline;
    if (vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &cpci, nullptr, &pipeline) != VK_SUCCESS)
        return fail(call + ": cannot create the compute pipeline of '" + shader.name + "'"), VK_NULL_HANDLE;
    setName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline), shader.name);
    if (executableStatistics_) reportShaderStatistics(pipeline, shader.name);
    pipelines_[key] = {pipeline, {shader.id}};
    return pipeline;
}

VkPipeline VulkanDevice::getGraphicsPipeline(const Program& program, const rhi::DrawCallState& s, Shader* vs,
                                             Shader* gs, Shader* fs, const std::string& call) {
    // The key: shaders, vertex layout, topology, target formats, blend, depth and raster state.
    KeyWriter k;
    k.key = "g";
    k.add(vs->id);
    k.add(gs ? gs->id : 0u);
    k.add(fs ? fs->id : 0u);
    k.add(s.vertexInputs.count);
    for (const auto& in : s.vertexInputs) {
        k.add(in.location), k.add(in.format), k.add(in.bufferIndex), k.add(in.offset);
    }
    k.add(s.vertexBuffers.count);
    for (const auto& vb : s.vertexBuffers) k.add(vb.stride), k.add(vb.perInstance);
    k.add(s.topology);
    k.add(s.colorTargets.count);
    std::vector<VkFormat> colorFormats;
    for (const auto& ct : s.colorTargets) {
        const rhi::TextureDesc* d = describe(ct.view.texture);
        rhi::Format f = ct.view.format != rhi::Format::Unknown ? ct.view.format : d->format;
        colorFormats.push_back(toVkFormat(f));
        k.add(colorFormats.back());
        const auto& b = ct.blend;
        k.add(b.enable), k.add(b.srcColor), k.add(b.dstColor), k.add(b.colorOp), k.add(b.srcAlpha);
        k.add(b.dstAlpha), k.add(b.alphaOp), k.add(b.writeMask);
    }
    VkFormat depthFormat = s.depthTarget.view.texture ? VK_FORMAT_D32_SFLOAT : VK_FORMAT_UNDEFINED;
    k.add(depthFormat);
    k.add(s.depth.testEnable), k.add(s.depth.writeEnable), k.add(s.depth.compare);
    k.add(s.raster.cull), k.add(s.raster.frontFace), k.add(s.raster.depthClamp);
    k.add(s.raster.depthBiasConstant), k.add(s.raster.depthBiasSlope);
    auto it = pipelines_.find(k.key);
    if (it != pipelines_.end()) return it->second.pipeline;

    std::vector<VkPipelineShaderStageCreateInfo> stages;
    for (auto [shader, stage] : {std::pair{vs, VK_SHADER_STAGE_VERTEX_BIT}, std::pair{gs, VK_SHADER_STAGE_GEOMETRY_BIT},
                                 std::pair{fs, VK_SHADER_STAGE_FRAGMENT_BIT}}) {
        if (!shader) continue;
        VkPipelineShaderStageCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage = stage;
        info.module = shader->module;
        info.pName = "main";
        stages.push_back(info);
    }
    std::vector<VkVertexInputBindingDescription> vbs;
    for (uint32_t i = 0; i < s.vertexBuffers.count; ++i)
        vbs.push_back({i, s.vertexBuffers[i].stride,
                       s.vertexBuffers[i].perInstance ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
    std::vector<VkVertexInputAttributeDescription> attrs;
    for (const auto& in : s.vertexInputs) attrs.push_back({in.location, in.bufferIndex, toVkVertexFormat(in.format), in.offset});
    VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = static_cast<uint32_t>(vbs.size());
    vi.pVertexBindingDescriptions = vbs.data();
    vi.vertexAttributeDescriptionCount = static_cast<uint32_t>(attrs.size());
    vi.pVertexAttributeDescriptions = attrs.data();
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = toVkTopology(s.topology);
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.depthClampEnable = s.raster.depthClamp;
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = toVkCullMode(s.raster.cull);
    // Plain Vulkan semantics: counter-clockwise in framebuffer coordinates (the GL backend matches).
    rs.frontFace = s.raster.frontFace == rhi::FrontFace::CounterClockwise ? VK_FRONT_FACE_COUNTER_CLOCKWISE
                                                                          : VK_FRONT_FACE_CLOCKWISE;
    rs.depthBiasEnable = s.raster.depthBiasConstant != 0.0f || s.raster.depthBiasSlope != 0.0f;
    rs.depthBiasConstantFactor = s.raster.depthBiasConstant;
    rs.depthBiasSlopeFactor = s.raster.depthBiasSlope;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = s.depth.testEnable;
    ds.depthWriteEnable = s.depth.writeEnable;
    ds.depthCompareOp = toVkCompareOp(s.depth.compare);
    std::vector<VkPipelineColorBlendAttachmentState> blends;
    for (const auto& ct : s.colorTargets) {
        const auto& b = ct.blend;
        VkPipelineColorBlendAttachmentState a{};
        a.blendEnable = b.enable;
        a.srcColorBlendFactor = toVkBlendFactor(b.srcColor);
        a.dstColorBlendFactor = toVkBlendFactor(b.dstColor);
        a.colorBlendOp = toVkBlendOp(b.colorOp);
        a.srcAlphaBlendFactor = toVkBlendFactor(b.srcAlpha);
        a.dstAlphaBlendFactor = toVkBlendFactor(b.dstAlpha);
        a.alphaBlendOp = toVkBlendOp(b.alphaOp);
        a.colorWriteMask = b.writeMask & 0xF;
        blends.push_back(a);
    }
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = static_cast<uint32_t>(blends.size());
    cb.pAttachments = blends.data();
    const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dyn.dynamicStateCount = 2;
    dyn.pDynamicStates = dynamic;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<uint32_t>(colorFormats.size());
    rendering.pColorAttachmentFormats = colorFormats.data();
    rendering.depthAttachmentFormat = depthFormat;

    VkGraphicsPipelineCreateInfo gci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    gci.pNext = &rendering;
    gci.stageCount = static_cast<uint32_t>(stages.size());
    gci.pStages = stages.data();
    gci.pVertexInputState = &vi;
    gci.pInputAssemblyState = &ia;
    gci.pViewportState = &vp;
    gci.pRasterizationState = &rs;
    gci.pMultisampleState = &ms;
    gci.pDepthStencilState = &ds;
    gci.pColorBlendState = &cb;
    gci.pDynamicState = &dyn;
    gci.layout = program.layout->pipelineLayout;
    VkPipeline pipeline;
    if (vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &gci, nullptr, &pipeline) != VK_SUCCESS)
        return fail(call + ": cannot create the graphics pipeline"), VK_NULL_HANDLE;
    setName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline),
            vs->name + (gs ? "+" + gs->name : "") + (fs ? "+" + fs->name : ""));
    std::vector<uint32_t> ids{vs->id};
    if (gs) ids.push_back(gs->id);
    if (fs) ids.push_back(fs->id);
    pipelines_[k.key] = {pipeline, ids};
    return pipeline;
}

void VulkanDevice::forgetShader(uint32_t shaderId) {
    // Pipelines and programs of a destroyed shader can never be hit again (ids are not reused): free them.
    VkDevice dev = device_;
    for (auto it = pipelines_.begin(); it != pipelines_.end();) {
        const auto& ids = it->second.shaderIds;
        if (std::find(ids.begin(), ids.end(), shaderId) != ids.end()) {
            VkPipeline p = it->second.pipeline;
            deferDestroy([dev, p] { vkDestroyPipeline(dev, p, nullptr); });
            it = pipelines_.erase(it);
        } else {
            ++it;
        }
    }
    for (auto it = programs_.begin(); it != programs_.end();) {
        const auto& ids = it->second->shaderIds;
        if (std::find(ids.begin(), ids.end(), shaderId) != ids.end())
            it = programs_.erase(it);
        else
            ++it;
    }
}

// One Info message per executable: "shader statistics 'NAME' (EXECUTABLE): Register Count 64, ...". The
// statistics' names and meanings are the driver's own.
void VulkanDevice::reportShaderStatistics(VkPipeline pipeline, const std::string& name) {
    VkPipelineInfoKHR info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
    info.pipeline = pipeline;
    uint32_t executables = 0;
    if (executableProperties_(device_, &info, &executables, nullptr) != VK_SUCCESS) return;
    std::vector<VkPipelineExecutablePropertiesKHR> properties(executables, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR});
    if (executableProperties_(device_, &info, &executables, properties.data()) != VK_SUCCESS) return;
    for (uint32_t e = 0; e < executables; ++e) {
        VkPipelineExecutableInfoKHR which{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
        which.pipeline = pipeline;
        which.executableIndex = e;
        uint32_t count = 0;
        if (executableStatistics_(device_, &which, &count, nullptr) != VK_SUCCESS) continue;
        std::vector<VkPipelineExecutableStatisticKHR> statistics(count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
        if (executableStatistics_(device_, &which, &count, statistics.data()) != VK_SUCCESS) continue;
        std::string line = "shader statistics '" + name + "' (" + properties[e].name + "):";
        for (uint32_t k = 0; k < count; ++k) {
            const VkPipelineExecutableStatisticKHR& st = statistics[k];
            line += std::string(k ? ", " : " ") + st.name + " ";
            switch (st.format) {
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: line += st.value.b32 ? "true" : "false"; break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: line += std::to_string(st.value.i64); break;
                case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: line += std::to_string(st.value.u64); break;
                default: line += std::to_string(st.value.f64); break;
            }
        }
        reporter_->report(rhi::Severity::Info, line);
    }
}

}  // namespace bricklight::vulkan::detail
