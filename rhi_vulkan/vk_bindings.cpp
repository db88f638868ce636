// Record bindings -> descriptors of set 0 and the declared accesses that drive the barriers. Everything a
// call needs is checked here, before anything is recorded, so that a failing call changes nothing.
#include <algorithm>
#include <cstring>

#include "vk_device.h"
#include "vk_formats.h"

namespace bricklight::vulkan::detail {

namespace {
template <typename T, size_t N>
const T* findSlot(const rhi::FixedVector<T, N>& v, uint8_t slot, size_t* index) {
    for (size_t i = 0; i < v.size(); ++i)
        if (v[i].slot == slot) return *index = i, &v[i];
    return nullptr;
}

const char* dimensionName(rhi::ResourceDimension d) {
    switch (d) {
        case rhi::ResourceDimension::Texture2D: return "2D";
        case rhi::ResourceDimension::Texture2DArray: return "2D array";
        case rhi::ResourceDimension::Texture3D: return "3D";
        case rhi::ResourceDimension::TextureCube: return "cube";
        default: return "buffer";
    }
}

const char* scalarName(rhi::ResourceScalar s) {
    switch (s) {
        case rhi::ResourceScalar::Float: return "float";
        case rhi::ResourceScalar::Uint: return "uint";
        case rhi::ResourceScalar::Sint: return "int";
        default: return "none";
    }
}

VkAccessFlags2 storageAccess(rhi::Access a) {
    switch (a) {
        case rhi::Access::Read: return VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
        case rhi::Access::Write: return VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
        default: return VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    }
}
}  // namespace

void VulkanDevice::addBufferUse(CallPlan& plan, Buffer& buffer, const AccessRequest& request) {
    for (auto& u : plan.buffers)
        if (u.buffer == &buffer) {
            u.request.merge(request);
            return;
        }
    plan.buffers.push_back({&buffer, request});
}

bool VulkanDevice::addTextureUse(CallPlan& plan, Texture& t, uint32_t baseMip, uint32_t mipCount, uint32_t baseLayer,
                                 uint32_t layerCount, const AccessRequest& request, const std::string& call,
                                 const std::string& what) {
    const bool seen = std::any_of(plan.textures.begin(), plan.textures.end(),
                                  [&](const CallPlan::TextureUse& u) { return u.texture == &t; });
    for (uint32_t mip = baseMip; mip < baseMip + mipCount; ++mip)
        for (uint32_t layer = baseLayer; layer < baseLayer + layerCount; ++layer) {
            bool merged = false;
            if (seen)
                for (auto& u : plan.textures)
                    if (u.texture == &t && u.mip == mip && u.layer == layer) {
                        if (!u.request.merge(request))
                            return fail(call + ": " + what + ": " + textureName(t) + " mip " + std::to_string(mip) +
                                        " layer " + std::to_string(layer) +
                                        " is used in two incompatible ways by this call (e.g. sampled and "
                                        "storage, or sampled and render target)");
                        merged = true;
                        break;
                    }
            if (!merged) plan.textures.push_back({&t, mip, layer, request});
        }
    return true;
}

bool VulkanDevice::planBindings(const Program& program, const rhi::Bindings& b, uint32_t flags,
                                const std::string& call, CallPlan& plan) {
    namespace TU = rhi::TextureUsage;
    namespace BU = rhi::BufferUsage;
    for (const ProgramBinding& pb : program.bindings) {
        const rhi::ReflectedBinding& refl = *pb.reflection;
        const std::string declared = std::string(rhi::bindingClassName(pb.cls)) + " slot " + std::to_string(pb.slot) +
                                     " ('" + refl.name + "')";
        CallPlan::Descriptor desc{};
        desc.binding = pb.binding;
        desc.type = pb.type;
        size_t index = 0;
        switch (pb.cls) {
            case rhi::BindingClass::Constants: {
                const rhi::ConstantsBinding* c = findSlot(b.constants, pb.slot, &index);
                if (!c) return fail(call + ": the shaders declare " + declared + " but the record binds none");
                const std::string where = call + ": constants[" + std::to_string(index) + "] (slot " +
                                          std::to_string(pb.slot) + ")";
                if (!c->data || !c->size) return fail(where + ": data is null or size is 0");
                if (c->size > rhi::kMaxConstantsBytes)
                    return fail(where + ": size " + std::to_string(c->size) + " exceeds kMaxConstantsBytes (256)");
                desc.constantsData = c->data;
                desc.constantsSize = c->size;
                // The shader may read its whole std140 block: short data is padded with zeros.
                desc.constantsRange = (std::max(c->size, refl.blockSize) + 15) / 16 * 16;
                break;
            }
            case rhi::BindingClass::ReadBuffer:
            case rhi::BindingClass::StorageBuffer: {
                const bool storage = pb.cls == rhi::BindingClass::StorageBuffer;
                rhi::BufferHandle handle;
                rhi::BufferRange range;
                rhi::Access access = rhi::Access::Read;
                if (storage) {
                    const auto* s = findSlot(b.storageBuffers, pb.slot, &index);
                    if (!s) return fail(call + ": the shaders declare " + declared + " but the record binds none");
                    handle = s->buffer, range = s->range, access = s->access;
                } else {
                    const auto* r = findSlot(b.readBuffers, pb.slot, &index);
                    if (!r) return fail(call + ": the shaders declare " + declared + " but the record binds none");
                    handle = r->buffer, range = r->range;
                }
                const std::string where = call + ": " + rhi::bindingClassName(pb.cls) + "[" + std::to_string(index) +
                                          "] (slot " + std::to_string(pb.slot) + ")";
                Buffer* buf = findBuffer(handle, where, "buffer");
                if (!buf) return false;
                if (!(buf->desc.usage & (BU::ShaderRead | BU::ShaderWrite)))
                    return fail(where + ": " + bufferName(*buf) + " was created without ShaderRead/ShaderWrite usage");
                const uint64_t size = buf->desc.size;
                if (range.offset >= size || (range.size && range.size > size - range.offset))
                    return fail(where + ": range [" + std::to_string(range.offset) + ", +" + std::to_string(range.size) +
                                ") is outside " + bufferName(*buf) + " (" + std::to_string(size) + " bytes)");
                const uint64_t bytes = range.size ? range.size : size - range.offset;
                if (range.offset % caps_.limits.minStorageBufferOffsetAlignment)
                    return fail(where + ": offset " + std::to_string(range.offset) +
                                " is not a multiple of minStorageBufferOffsetAlignment (" +
                                std::to_string(caps_.limits.minStorageBufferOffsetAlignment) + ")");
                if (bytes > caps_.limits.maxStorageBufferRange)
                    return fail(where + ": " + std::to_string(bytes) + " bytes exceed maxStorageBufferRange");
                if (bytes < refl.blockSize)
                    return fail(where + ": " + std::to_string(bytes) + " bytes are fewer than the " +
                                std::to_string(refl.blockSize) + " bytes the shader's block '" + refl.name + "' needs");
                desc.buffer = {buf->buffer, range.offset, bytes};
                AccessRequest req;
                req.stages = pb.pipelineStages;
                req.access = storageAccess(access);
                req.write = rhi::accessWrites(access);
                req.shaderWriteOnly = access == rhi::Access::Write || access == rhi::Access::Atomic;
                req.noBarrierWithPreviousWriter = flags & rhi::DispatchFlags::NoBarrierWithPreviousWriter;
                addBufferUse(plan, *buf, req);
                break;
            }
            case rhi::BindingClass::Texture:
            case rhi::BindingClass::StorageImage: {
                const bool sampled = pb.cls == rhi::BindingClass::Texture;
                rhi::TextureView view;
                rhi::Access access = rhi::Access::Read;
                Sampler* sampler = nullptr;
                std::string where;
                if (sampled) {
                    const auto* tb = findSlot(b.textures, pb.slot, &index);
                    if (!tb) return fail(call + ": the shaders declare " + declared + " but the record binds none");
                    where = call + ": textures[" + std::to_string(index) + "] (slot " + std::to_string(pb.slot) + ")";
                    view = tb->view;
                    sampler = findSampler(tb->sampler, where, "sampler");
                    if (!sampler) return false;
                } else {
                    const auto* sb = findSlot(b.storageImages, pb.slot, &index);
                    if (!sb) return fail(call + ": the shaders declare " + declared + " but the record binds none");
                    where = call + ": storageImages[" + std::to_string(index) + "] (slot " + std::to_string(pb.slot) + ")";
                    view = sb->view;
                    access = sb->access;
                }
                Texture* t = findTexture(view.texture, where, "texture");
                if (!t) return false;
                const rhi::TextureDesc& td = t->desc;
                const std::string tname = textureName(*t);
                if (!(td.usage & (sampled ? TU::Sampled : TU::Storage)))
                    return fail(where + ": " + tname + " was created without " + (sampled ? "Sampled" : "Storage") +
                                " usage");
                rhi::Format fmt = view.format == rhi::Format::Unknown ? td.format : view.format;
                if (!viewFormatCompatible(td.format, fmt))
                    return fail(where + ": view format " + rhi::formatName(fmt) + " cannot reinterpret " + tname +
                                " of format " + rhi::formatName(td.format));
                if (sampled) {
                    if (!caps_.supports(fmt, rhi::FormatSupport::Sampled))
                        return fail(where + ": format " + rhi::formatName(fmt) + " cannot be sampled on this device");
                    const auto& sd = sampler->desc;
                    const bool linear = sd.minFilter == rhi::Filter::Linear || sd.magFilter == rhi::Filter::Linear ||
                                        sd.mipFilter == rhi::Filter::Linear;
                    if (linear && !caps_.supports(fmt, rhi::FormatSupport::Filterable))
                        return fail(where + ": format " + rhi::formatName(fmt) +
                                    " is not filterable; use a Nearest sampler");
                } else {
                    if (!caps_.supports(fmt, rhi::FormatSupport::Storage))
                        return fail(where + ": " + tname + " format " + rhi::formatName(fmt) +
                                    " is not storage-capable" +
                                    (fmt == rhi::Format::RGBA8_SRGB ? " (bind an RGBA8_UNORM view)" : ""));
                    if (access == rhi::Access::Atomic && !caps_.supports(fmt, rhi::FormatSupport::StorageAtomic))
                        return fail(where + ": format " + rhi::formatName(fmt) + " does not support image atomics");
                    if (refl.imageFormat && refl.imageFormat != static_cast<uint8_t>(fmt))
                        return fail(where + ": view format " + rhi::formatName(fmt) + " differs from the shader's " +
                                    rhi::formatName(static_cast<rhi::Format>(refl.imageFormat)) + " ('" + refl.name +
                                    "')");
                }
                if (refl.scalar != rhi::ResourceScalar::None && formatScalar(fmt) != refl.scalar)
                    return fail(where + ": format " + rhi::formatName(fmt) + " returns " + scalarName(formatScalar(fmt)) +
                                " but '" + refl.name + "' is a " + scalarName(refl.scalar) + " sampler/image");
                // Subresource range.
                if (view.baseMip >= td.mipLevels)
                    return fail(where + ": baseMip " + std::to_string(view.baseMip) + " is outside " + tname + " (" +
                                std::to_string(td.mipLevels) + " mips)");
                uint32_t mipCount = view.mipCount ? view.mipCount : td.mipLevels - view.baseMip;
                if (view.baseMip + mipCount > td.mipLevels)
                    return fail(where + ": mips [" + std::to_string(view.baseMip) + ", +" + std::to_string(mipCount) +
                                ") are outside " + tname);
                if (!sampled) mipCount = 1;  // storage images bind one mip (baseMip) with all its layers
                if (view.baseLayer >= t->layers)
                    return fail(where + ": baseLayer " + std::to_string(view.baseLayer) + " is outside " + tname + " (" +
                                std::to_string(t->layers) + " layers)");
                uint32_t layerCount = view.layerCount ? view.layerCount : t->layers - view.baseLayer;
                if (view.baseLayer + layerCount > t->layers)
                    return fail(where + ": layers [" + std::to_string(view.baseLayer) + ", +" +
                                std::to_string(layerCount) + ") are outside " + tname);
                // The shader's declared dimension decides the view type.
                const bool is3D = td.dimension == rhi::TextureDimension::Texture3D;
                VkImageViewType type = VK_IMAGE_VIEW_TYPE_2D;
                auto mismatch = [&] {
                    return fail(where + ": '" + refl.name + "' is a " + dimensionName(refl.dimension) +
                                " binding but " + tname + " is a " + rhi::textureDimensionName(td.dimension) +
                                " texture");
                };
                switch (refl.dimension) {
                    case rhi::ResourceDimension::Texture2D:
                        if (is3D) return mismatch();
                        layerCount = 1;  // a 2D binding sees the view's first layer
                        break;
                    case rhi::ResourceDimension::Texture2DArray:
                        if (is3D) return mismatch();
                        type = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
                        break;
                    case rhi::ResourceDimension::TextureCube:
                        if (td.dimension != rhi::TextureDimension::TextureCube) return mismatch();
                        if (view.baseLayer != 0 || layerCount != 6)
                            return fail(where + ": a cube binding needs all 6 layers of " + tname);
                        type = VK_IMAGE_VIEW_TYPE_CUBE;
                        break;
                    case rhi::ResourceDimension::Texture3D:
                        if (!is3D) return mismatch();
                        type = VK_IMAGE_VIEW_TYPE_3D;
                        break;
                    default: return mismatch();
                }
                // Sampled depth uses the depth read-only layout, which Vulkan only allows on images that can
                // be depth attachments; a sampled-only depth texture uses SHADER_READ_ONLY_OPTIMAL. A colour
                // texture that is also a storage image is sampled in GENERAL: passes that write it and passes
                // that sample it then need only a memory dependency, not a layout transition, and that can
                // share one global barrier with the call's other hazards (docs/backend_vulkan.md, Barriers).
                const bool depthReadOnly = isDepthFormat(fmt) && (td.usage & TU::DepthTarget);
                const bool storageCapable = (td.usage & TU::Storage) && !isDepthFormat(fmt);
                const VkImageLayout layout = !sampled || storageCapable ? VK_IMAGE_LAYOUT_GENERAL
                                             : depthReadOnly ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                                             : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
                ViewKey key{toVkFormat(fmt), type, VkImageUsageFlags(sampled ? VK_IMAGE_USAGE_SAMPLED_BIT
                                                                              : VK_IMAGE_USAGE_STORAGE_BIT),
                            view.baseMip, mipCount, view.baseLayer, layerCount};
                VkImageView imageView = getView(*t, key);
                if (!imageView) return fail(where + ": cannot create a view of " + tname);
                desc.image = {sampled ? sampler->sampler : VK_NULL_HANDLE, imageView, layout};
                AccessRequest req;
                req.stages = pb.pipelineStages;
                req.access = sampled ? VK_ACCESS_2_SHADER_SAMPLED_READ_BIT : storageAccess(access);
                req.layout = layout;
                req.sampled = sampled;
                req.write = !sampled && rhi::accessWrites(access);
                req.shaderWriteOnly = !sampled && (access == rhi::Access::Write || access == rhi::Access::Atomic);
                req.noBarrierWithPreviousWriter = flags & rhi::DispatchFlags::NoBarrierWithPreviousWriter;
                if (!addTextureUse(plan, *t, view.baseMip, mipCount, is3D ? 0 : view.baseLayer, is3D ? 1 : layerCount,
                                   req, where, "texture"))
                    return false;
                break;
            }
        }
        plan.descriptors.push_back(desc);
    }
    return true;
}

VkDescriptorSet VulkanDevice::allocateDescriptorSet(VkDescriptorSetLayout layout) {
    FrameSlot& slot = frame();
    for (int attempt = 0; attempt < 2; ++attempt) {
        if (slot.currentDescriptorPool < slot.descriptorPools.size()) {
            VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
            ai.descriptorPool = slot.descriptorPools[slot.currentDescriptorPool];
            ai.descriptorSetCount = 1;
            ai.pSetLayouts = &layout;
            VkDescriptorSet set;
            if (vkAllocateDescriptorSets(device_, &ai, &set) == VK_SUCCESS) return set;
            slot.currentDescriptorPool++;
        }
        if (slot.currentDescriptorPool >= slot.descriptorPools.size()) {
            const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1024},
                                                  {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2048},
                                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2048},
                                                  {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1024}};
            VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
            pci.maxSets = 256;
            pci.poolSizeCount = 4;
            pci.pPoolSizes = sizes;
            VkDescriptorPool pool;
            if (vkCreateDescriptorPool(device_, &pci, nullptr, &pool) != VK_SUCCESS) return VK_NULL_HANDLE;
            slot.descriptorPools.push_back(pool);
            slot.currentDescriptorPool = slot.descriptorPools.size() - 1;
        }
    }
    return VK_NULL_HANDLE;
}

bool VulkanDevice::bindDescriptors(VkCommandBuffer c, VkPipelineBindPoint bindPoint, const Program& program,
                                   CallPlan& plan) {
    if (plan.descriptors.empty()) return true;
    // Constants are copied now, into this frame's upload ring.
    for (auto& d : plan.descriptors) {
        if (!d.constantsData) continue;
        UploadAllocation up = allocateUpload(d.constantsRange, caps_.limits.minUniformBufferOffsetAlignment);
        if (!up.buffer) return fail("out of host memory for constants");
        memcpy(up.mapped, d.constantsData, d.constantsSize);
        memset(up.mapped + d.constantsSize, 0, d.constantsRange - d.constantsSize);
        d.buffer = {up.buffer, up.offset, d.constantsRange};
    }
    std::vector<VkWriteDescriptorSet> writes;
    writes.reserve(plan.descriptors.size());
    for (auto& d : plan.descriptors) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = d.binding;
        w.descriptorCount = 1;
        w.descriptorType = d.type;
        if (d.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || d.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
            w.pBufferInfo = &d.buffer;
        else
            w.pImageInfo = &d.image;
        writes.push_back(w);
    }
    if (program.layout->push) {
        pushDescriptorSet_(c, bindPoint, program.layout->pipelineLayout, 0, static_cast<uint32_t>(writes.size()),
                           writes.data());
        return true;
    }
    VkDescriptorSet set = allocateDescriptorSet(program.layout->setLayout);
    if (!set) return fail("cannot allocate a descriptor set");
    for (auto& w : writes) w.dstSet = set;
    vkUpdateDescriptorSets(device_, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
    vkCmdBindDescriptorSets(c, bindPoint, program.layout->pipelineLayout, 0, 1, &set, 0, nullptr);
    return true;
}

}  // namespace bricklight::vulkan::detail
