// Resource creation, wrapping, lookup and (deferred) destruction.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "../rhi/size_math.h"
#include "vk_device.h"
#include "vk_formats.h"

namespace bricklight::vulkan::detail {

namespace {
template <typename Map>
std::string missing(const Map& map, uint32_t id, uint32_t nextId, const std::string& call, const char* what,
                    const char* kind) {
    (void)map;
    std::string s = call + ": " + what + ": " + kind + " handle " + std::to_string(id);
    return s + (id < nextId ? " was destroyed" : " is not a handle this device issued");
}

std::string bytesText(uint64_t bytes) { return std::to_string(bytes) + " bytes"; }
}  // namespace

bool VulkanDevice::checkAllocationSize(uint64_t bytes, const std::string& call, const char* what) {
    if (bytes <= maxAllocationBytes_) return true;
    return fail(call + ": " + what + " of " + bytesText(bytes) + " exceeds what one allocation may hold on this device (" +
                bytesText(maxAllocationBytes_) + ")");
}

bool VulkanDevice::checkBufferSize(const rhi::BufferDesc& desc, const std::string& call) {
    if (desc.size == 0) return fail(call + ": size is 0");
    if (desc.size > maxBufferBytes_)
        return fail(call + ": size " + std::to_string(desc.size) + " exceeds the largest buffer this device can hold (" +
                    bytesText(maxBufferBytes_) + ")");
    return true;
}

Texture* VulkanDevice::findTexture(rhi::TextureHandle h, const std::string& call, const char* what) {
    if (!h) return fail(call + ": " + what + " is a null texture handle"), nullptr;
    auto it = textures_.find(h.id);
    if (it == textures_.end()) return fail(missing(textures_, h.id, nextTextureId_, call, what, "texture")), nullptr;
    return it->second.get();
}
Buffer* VulkanDevice::findBuffer(rhi::BufferHandle h, const std::string& call, const char* what) {
    if (!h) return fail(call + ": " + what + " is a null buffer handle"), nullptr;
    auto it = buffers_.find(h.id);
    if (it == buffers_.end()) return fail(missing(buffers_, h.id, nextBufferId_, call, what, "buffer")), nullptr;
    return it->second.get();
}
Sampler* VulkanDevice::findSampler(rhi::SamplerHandle h, const std::string& call, const char* what) {
    if (!h) return fail(call + ": " + what + " is a null sampler handle"), nullptr;
    auto it = samplers_.find(h.id);
    if (it == samplers_.end()) return fail(missing(samplers_, h.id, nextSamplerId_, call, what, "sampler")), nullptr;
    return it->second.get();
}
Shader* VulkanDevice::findShader(rhi::ShaderHandle h, const std::string& call, const char* what) {
    if (!h) return fail(call + ": " + what + " is a null shader handle"), nullptr;
    auto it = shaders_.find(h.id);
    if (it == shaders_.end()) return fail(missing(shaders_, h.id, nextShaderId_, call, what, "shader")), nullptr;
    return it->second.get();
}

namespace {
// "<kind> '<name>'", or "<kind> '#<id>'" when unnamed. (Appended piece by piece: GCC 12 at -O3 warns falsely on
// "literal" + std::string&&, its bug 105651.)
std::string resourceName(const char* kind, const std::string& debugName, uint64_t id) {
    std::string name(kind);
    name.append(" '");
    if (debugName.empty()) name.append("#").append(std::to_string(id));
    else name.append(debugName);
    return name.append("'");
}
}  // namespace

std::string VulkanDevice::textureName(const Texture& t) const { return resourceName("texture", t.desc.debugName, t.id); }
std::string VulkanDevice::bufferName(const Buffer& b) const { return resourceName("buffer", b.desc.debugName, b.id); }

const rhi::TextureDesc* VulkanDevice::describe(rhi::TextureHandle h) const {
    auto it = textures_.find(h.id);
    return it == textures_.end() ? nullptr : &it->second->desc;
}
const rhi::BufferDesc* VulkanDevice::describe(rhi::BufferHandle h) const {
    auto it = buffers_.find(h.id);
    return it == buffers_.end() ? nullptr : &it->second->desc;
}
VkImage VulkanDevice::nativeImage(rhi::TextureHandle h) const {
    auto it = textures_.find(h.id);
    return it == textures_.end() ? VK_NULL_HANDLE : it->second->image;
}
VkBuffer VulkanDevice::nativeBuffer(rhi::BufferHandle h) const {
    auto it = buffers_.find(h.id);
    return it == buffers_.end() ? VK_NULL_HANDLE : it->second->buffer;
}

bool VulkanDevice::checkTextureDesc(const rhi::TextureDesc& d, const std::string& call) {
    using rhi::TextureDimension;
    namespace U = rhi::TextureUsage;
    namespace S = rhi::FormatSupport;
    if (d.format == rhi::Format::Unknown || d.format >= rhi::Format::Count) return fail(call + ": format is Unknown");
    if (d.dimension > TextureDimension::TextureCube)
        return fail(call + ": dimension " + std::to_string(int(d.dimension)) + " is not a TextureDimension");
    if (!d.width || !d.height || !d.depthOrLayers)
        return fail(call + ": size " + std::to_string(d.width) + "x" + std::to_string(d.height) + "x" +
                    std::to_string(d.depthOrLayers) + " has a zero dimension");
    const uint32_t maxDim = d.dimension == TextureDimension::Texture3D ? caps_.limits.maxTextureSize3D
                                                                       : caps_.limits.maxTextureSize2D;
    if (d.width > maxDim || d.height > maxDim ||
        (d.dimension == TextureDimension::Texture3D && d.depthOrLayers > maxDim))
        return fail(call + ": size exceeds the device limit " + std::to_string(maxDim));
    if (d.dimension == TextureDimension::Texture2D && d.depthOrLayers != 1)
        return fail(call + ": depthOrLayers must be 1 for a 2D texture");
    if (d.dimension == TextureDimension::Texture2DArray && d.depthOrLayers > caps_.limits.maxTextureArrayLayers)
        return fail(call + ": " + std::to_string(d.depthOrLayers) + " layers exceed maxTextureArrayLayers");
    if (d.dimension == TextureDimension::TextureCube && (d.depthOrLayers != 6 || d.width != d.height))
        return fail(call + ": a cube needs depthOrLayers 6 and square faces");
    const uint32_t maxMips = rhi::sizes::fullMipCount(rhi::sizes::largestExtent(d));
    if (d.mipLevels == 0 || d.mipLevels > maxMips)
        return fail(call + ": mipLevels " + std::to_string(d.mipLevels) + " is out of range (1.." + std::to_string(maxMips) + ")");
    // Every extent is within the limits here, so the count fits 64 bits; refuse what no allocation can hold.
    const auto bytes = rhi::sizes::textureBytes(d);
    if (!bytes) return fail(call + ": the texture's size in bytes does not fit 64 bits");
    if (!checkAllocationSize(*bytes, call, "a texture")) return false;
    if (d.usage & ~uint32_t(U::Sampled | U::Storage | U::RenderTarget | U::DepthTarget))
        return fail(call + ": usage has unknown bits");
    const bool depthFormat = isDepthFormat(d.format);
    const char* fmt = rhi::formatName(d.format);
    if (depthFormat && (d.usage & (U::Storage | U::RenderTarget)))
        return fail(call + ": depth format " + fmt + " cannot be a storage image or colour render target");
    if (!depthFormat && (d.usage & U::DepthTarget))
        return fail(call + ": DepthTarget usage needs a depth format, not " + fmt);
    if (depthFormat && d.dimension == TextureDimension::Texture3D)
        return fail(call + ": a 3D texture cannot have a depth format");
    struct Need {
        uint32_t usage, bit;
        const char* name;
    } needs[] = {{U::Sampled, S::Sampled, "Sampled"}, {U::Storage, S::Storage, "Storage"},
                 {U::RenderTarget, S::RenderTarget, "RenderTarget"}, {U::DepthTarget, S::DepthTarget, "DepthTarget"}};
    for (const Need& n : needs) {
        if (!(d.usage & n.usage)) continue;
        rhi::Format f = d.format;
        // sRGB formats are never storage-capable; a storage texture of one is written through UNORM views.
        if (n.usage == U::Storage && f == rhi::Format::RGBA8_SRGB) f = rhi::Format::RGBA8_UNORM;
        if (!caps_.supports(f, n.bit))
            return fail(call + ": format " + fmt + " does not support " + n.name + " on this device");
    }
    return true;
}

Texture* VulkanDevice::addTexture(const rhi::TextureDesc& desc, VkImage image, VkDeviceMemory memory, bool wrapped) {
    auto t = std::make_unique<Texture>();
    t->id = nextTextureId_++;
    t->desc = desc;
    t->image = image;
    t->memory = memory;
    t->wrapped = wrapped;
    t->format = toVkFormat(desc.format);
    t->aspect = isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    t->layers = rhi::textureLayerCount(desc);
    t->subresources.resize(size_t(desc.mipLevels) * t->layers);
    Texture* raw = t.get();
    textures_[raw->id] = std::move(t);
    return raw;
}

rhi::TextureHandle VulkanDevice::createTexture(const rhi::TextureDesc& desc, const void* initialData) {
    const std::string call = "createTexture" + quoted(desc.debugName.c_str());
    if (!checkTextureDesc(desc, call)) return {};
    namespace U = rhi::TextureUsage;
    using rhi::TextureDimension;
    const bool depthFormat = isDepthFormat(desc.format);
    VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ici.imageType = desc.dimension == TextureDimension::Texture3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    ici.format = toVkFormat(desc.format);
    ici.extent = {desc.width, desc.height, desc.dimension == TextureDimension::Texture3D ? desc.depthOrLayers : 1};
    ici.mipLevels = desc.mipLevels;
    ici.arrayLayers = rhi::textureLayerCount(desc);
    ici.samples = VK_SAMPLE_COUNT_1_BIT;
    ici.tiling = VK_IMAGE_TILING_OPTIMAL;
    ici.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (desc.usage & U::Sampled) ici.usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
    if (desc.usage & U::Storage) ici.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    if (desc.usage & U::RenderTarget) ici.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if (desc.usage & U::DepthTarget) ici.usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    // Views may reinterpret same-size colour formats; EXTENDED_USAGE lets an sRGB image carry STORAGE for
    // its UNORM views even though the sRGB format itself cannot be a storage image.
    if (!depthFormat) ici.flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
    if (desc.dimension == TextureDimension::TextureCube) ici.flags |= VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
    if (desc.dimension == TextureDimension::Texture3D && (desc.usage & U::RenderTarget))
        ici.flags |= VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT;  // slices of a 3D texture as colour targets
    ici.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;

    VkImageFormatProperties ifp;
    if (vkGetPhysicalDeviceImageFormatProperties(physical_, ici.format, ici.imageType, ici.tiling, ici.usage, ici.flags,
                                                 &ifp) != VK_SUCCESS ||
        ifp.maxMipLevels < ici.mipLevels || ifp.maxArrayLayers < ici.arrayLayers || ifp.maxExtent.width < desc.width ||
        ifp.maxExtent.height < desc.height || ifp.maxExtent.depth < ici.extent.depth)
        return fail(call + ": this device cannot create a " + rhi::textureDimensionName(desc.dimension) + " " +
                    rhi::formatName(desc.format) + " texture of this size/usage"),
               rhi::TextureHandle{};
    if (const uint64_t bytes = *rhi::sizes::textureBytes(desc); bytes > ifp.maxResourceSize)
        return fail(call + ": " + bytesText(bytes) + " exceed the device's maxResourceSize for this format (" +
                    bytesText(ifp.maxResourceSize) + ")"),
               rhi::TextureHandle{};

    VkImage image = VK_NULL_HANDLE;
    if (vkCreateImage(device_, &ici, nullptr, &image) != VK_SUCCESS)
        return fail(call + ": vkCreateImage failed"), rhi::TextureHandle{};
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device_, image, &requirements);
    if (!checkAllocationSize(requirements.size, call, "the image's memory")) {
        vkDestroyImage(device_, image, nullptr);
        return {};
    }
    VkDeviceMemory memory = VK_NULL_HANDLE;
    if (!allocateImageMemory(image, &memory)) {
        vkDestroyImage(device_, image, nullptr);
        return fail(call + ": out of device memory"), rhi::TextureHandle{};
    }
    Texture* t = addTexture(desc, image, memory, false);
    setName(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<uint64_t>(image), desc.debugName);
    if (initialData) {
        uploadInitialTexture(*t, initialData);
    } else {
        // New textures read as zero on every backend, which keeps cross-backend comparisons deterministic.
        rhi::ClearValue zero{};
        clearTexture(rhi::TextureHandle{t->id}, 0, desc.mipLevels, zero);
    }
    return rhi::TextureHandle{t->id};
}

void VulkanDevice::uploadInitialTexture(Texture& t, const void* data) {
    // Tightly packed: all mips of layer 0, then layer 1...; each region goes to its own aligned staging
    // offset so that every copy region meets bufferOffset alignment.
    const rhi::TextureDesc& d = t.desc;
    const uint32_t bpp = rhi::formatInfo(d.format).bytesPerTexel;
    VkDeviceSize total = 0;
    for (uint32_t layer = 0; layer < t.layers; ++layer)
        for (uint32_t mip = 0; mip < d.mipLevels; ++mip)
            total += (uint64_t(rhi::mipExtent(d.width, mip)) * rhi::mipExtent(d.height, mip) * rhi::textureDepth(d, mip) *
                          bpp + 15) / 16 * 16;
    UploadAllocation up = allocateUpload(total, 16);
    if (!up.buffer) {
        fail("createTexture" + quoted(d.debugName.c_str()) + ": out of host memory for the initial data");
        return;
    }
    std::vector<VkBufferImageCopy> regions;
    const uint8_t* src = static_cast<const uint8_t*>(data);
    VkDeviceSize dst = 0;
    for (uint32_t layer = 0; layer < t.layers; ++layer)
        for (uint32_t mip = 0; mip < d.mipLevels; ++mip) {
            VkBufferImageCopy r{};
            r.bufferOffset = up.offset + dst;
            r.imageSubresource = {t.aspect, mip, layer, 1};
            r.imageExtent = {rhi::mipExtent(d.width, mip), rhi::mipExtent(d.height, mip), rhi::textureDepth(d, mip)};
            const uint64_t bytes = uint64_t(r.imageExtent.width) * r.imageExtent.height * r.imageExtent.depth * bpp;
            memcpy(up.mapped + dst, src, bytes);
            src += bytes;
            dst += (bytes + 15) / 16 * 16;
            regions.push_back(r);
        }
    CallPlan plan;
    AccessRequest req;
    req.stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    req.access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    req.layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    req.write = true;
    req.shaderWriteOnly = false;
    addTextureUse(plan, t, 0, d.mipLevels, 0, t.layers, req, "", "");
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    vkCmdCopyBufferToImage(c, up.buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           static_cast<uint32_t>(regions.size()), regions.data());
    releaseWrapped(c, plan);
}

rhi::BufferHandle VulkanDevice::createBuffer(const rhi::BufferDesc& desc, const void* initialData) {
    const std::string call = "createBuffer" + quoted(desc.debugName.c_str());
    namespace U = rhi::BufferUsage;
    if (!checkBufferSize(desc, call)) return {};
    if (desc.usage & ~uint32_t(U::ShaderRead | U::ShaderWrite | U::IndirectArgs | U::Vertex | U::Index))
        return fail(call + ": usage has unknown bits"), rhi::BufferHandle{};
    if (desc.structStride && desc.size % desc.structStride)
        return fail(call + ": size " + std::to_string(desc.size) + " is not a multiple of structStride " +
                    std::to_string(desc.structStride)),
               rhi::BufferHandle{};
    VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (desc.usage & (U::ShaderRead | U::ShaderWrite)) usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (desc.usage & U::IndirectArgs) usage |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    if (desc.usage & U::Vertex) usage |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    if (desc.usage & U::Index) usage |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    VkBuffer buffer;
    VkDeviceMemory memory;
    // Round up to 4 so that whole-buffer fills and copies stay legal for odd sizes.
    if (!allocateBuffer((desc.size + 3) / 4 * 4, usage, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &buffer, &memory, nullptr))
        return fail(call + ": cannot allocate " + std::to_string(desc.size) + " bytes"), rhi::BufferHandle{};
    auto b = std::make_unique<Buffer>();
    b->id = nextBufferId_++;
    b->desc = desc;
    b->buffer = buffer;
    b->memory = memory;
    const rhi::BufferHandle handle{b->id};
    setName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(buffer), desc.debugName);
    buffers_[b->id] = std::move(b);
    if (initialData)
        writeBuffer(handle, 0, initialData, desc.size);
    else
        clearBuffer(handle, rhi::BufferRange{0, 0}, 0);  // new buffers read as zero on every backend
    return handle;
}

rhi::SamplerHandle VulkanDevice::createSampler(const rhi::SamplerDesc& d) {
    const std::string call = "createSampler" + quoted(d.debugName.c_str());
    if (!(d.maxAnisotropy >= 1.0f)) return fail(call + ": maxAnisotropy must be >= 1"), rhi::SamplerHandle{};
    if (!(d.minLod <= d.maxLod)) return fail(call + ": minLod is greater than maxLod"), rhi::SamplerHandle{};
    if (!(std::fabs(d.mipLodBias) <= props_.limits.maxSamplerLodBias))
        return fail(call + ": mipLodBias " + std::to_string(d.mipLodBias) + " exceeds maxSamplerLodBias " +
                    std::to_string(props_.limits.maxSamplerLodBias)),
               rhi::SamplerHandle{};
    if (int(d.minFilter) > 1 || int(d.magFilter) > 1 || int(d.mipFilter) > 1 || int(d.addressU) > 3 || int(d.addressV) > 3 ||
        int(d.addressW) > 3 || int(d.borderColor) > 2 || int(d.compareOp) > 7)
        return fail(call + ": a filter, address mode, border colour or compare op is out of its enum's range"),
               rhi::SamplerHandle{};
    VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sci.magFilter = toVkFilter(d.magFilter);
    sci.minFilter = toVkFilter(d.minFilter);
    sci.mipmapMode = toVkMipmapMode(d.mipFilter);
    sci.addressModeU = toVkAddressMode(d.addressU);
    sci.addressModeV = toVkAddressMode(d.addressV);
    sci.addressModeW = toVkAddressMode(d.addressW);
    sci.mipLodBias = d.mipLodBias;
    // Anisotropy is a hint: without the feature (or above the limit) it is clamped, as GL does.
    sci.anisotropyEnable = d.maxAnisotropy > 1.0f && enabled_.samplerAnisotropy;
    sci.maxAnisotropy = std::min(d.maxAnisotropy, props_.limits.maxSamplerAnisotropy);
    sci.compareEnable = d.compareEnable;
    sci.compareOp = toVkCompareOp(d.compareOp);
    sci.minLod = d.minLod;
    sci.maxLod = d.maxLod;
    sci.borderColor = toVkBorderColor(d.borderColor);
    VkSampler sampler;
    if (vkCreateSampler(device_, &sci, nullptr, &sampler) != VK_SUCCESS)
        return fail(call + ": vkCreateSampler failed"), rhi::SamplerHandle{};
    auto s = std::make_unique<Sampler>();
    s->id = nextSamplerId_++;
    s->desc = d;
    s->sampler = sampler;
    setName(VK_OBJECT_TYPE_SAMPLER, reinterpret_cast<uint64_t>(sampler), d.debugName);
    const uint32_t id = s->id;
    samplers_[id] = std::move(s);
    return rhi::SamplerHandle{id};
}

rhi::ShaderHandle VulkanDevice::createShader(const rhi::ShaderDesc& d) {
    std::string name = !d.debugName.empty() ? d.debugName : (d.blob && d.blob->name ? d.blob->name : "");
    const std::string call = "createShader" + quoted(name.c_str());
    if (!d.blob) return fail(call + ": blob is null"), rhi::ShaderHandle{};
    if (!d.blob->spirv || !d.blob->spirvWords) return fail(call + ": the blob has no SPIR-V"), rhi::ShaderHandle{};
    if (d.blob->stage == rhi::ShaderStage::Geometry && !enabled_.geometryShader)
        return fail(call + ": geometry shaders are not supported on this device"), rhi::ShaderHandle{};
    VkShaderModuleCreateInfo smci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    smci.codeSize = d.blob->spirvWords * 4;
    smci.pCode = d.blob->spirv;
    VkShaderModule module;
    if (vkCreateShaderModule(device_, &smci, nullptr, &module) != VK_SUCCESS)
        return fail(call + ": vkCreateShaderModule failed"), rhi::ShaderHandle{};
    auto s = std::make_unique<Shader>();
    s->id = nextShaderId_++;
    s->name = name;
    s->blob = d.blob;
    s->module = module;
    setName(VK_OBJECT_TYPE_SHADER_MODULE, reinterpret_cast<uint64_t>(module), name);
    const uint32_t id = s->id;
    shaders_[id] = std::move(s);
    return rhi::ShaderHandle{id};
}

rhi::TextureHandle VulkanDevice::wrapNativeTexture(const rhi::TextureDesc& desc, rhi::NativeObject native) {
    const std::string call = "wrapNativeTexture" + quoted(desc.debugName.c_str());
    if (!native.object) return fail(call + ": native.object (VkImage) is null"), rhi::TextureHandle{};
    if (!checkTextureDesc(desc, call)) return {};
    Texture* t = addTexture(desc, reinterpret_cast<VkImage>(native.object), VK_NULL_HANDLE, true);
    t->nativeLayout = static_cast<VkImageLayout>(native.aux);
    // The application may have written the image in any way before each call: start from a full write.
    for (AccessState& s : t->subresources) {
        s.layout = t->nativeLayout;
        s.writeStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        s.writeAccess = VK_ACCESS_2_MEMORY_WRITE_BIT;
    }
    return rhi::TextureHandle{t->id};
}

rhi::BufferHandle VulkanDevice::wrapNativeBuffer(const rhi::BufferDesc& desc, rhi::NativeObject native) {
    const std::string call = "wrapNativeBuffer" + quoted(desc.debugName.c_str());
    if (!native.object) return fail(call + ": native.object (VkBuffer) is null"), rhi::BufferHandle{};
    // Vulkan cannot tell a VkBuffer's size: desc.size is trusted, but never beyond what a buffer may be.
    if (!checkBufferSize(desc, call)) return {};
    auto b = std::make_unique<Buffer>();
    b->id = nextBufferId_++;
    b->desc = desc;
    b->buffer = reinterpret_cast<VkBuffer>(native.object);
    b->wrapped = true;
    b->state.writeStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b->state.writeAccess = VK_ACCESS_2_MEMORY_WRITE_BIT;
    const uint32_t id = b->id;
    buffers_[id] = std::move(b);
    return rhi::BufferHandle{id};
}

void VulkanDevice::destroy(rhi::TextureHandle h) {
    if (!h) return;
    Texture* t = findTexture(h, "destroy(texture)", "texture");
    if (!t) return;
    VkDevice dev = device_;
    auto views = t->views;
    VkImage image = t->wrapped ? VK_NULL_HANDLE : t->image;
    VkDeviceMemory memory = t->memory;
    deferDestroy([dev, views, image, memory] {
        for (auto& v : views) vkDestroyImageView(dev, v.second, nullptr);
        if (image) vkDestroyImage(dev, image, nullptr);
        if (memory) vkFreeMemory(dev, memory, nullptr);
    });
    textures_.erase(h.id);
}

void VulkanDevice::destroy(rhi::BufferHandle h) {
    if (!h) return;
    Buffer* b = findBuffer(h, "destroy(buffer)", "buffer");
    if (!b) return;
    VkDevice dev = device_;
    VkBuffer buffer = b->wrapped ? VK_NULL_HANDLE : b->buffer;
    VkDeviceMemory memory = b->memory;
    deferDestroy([dev, buffer, memory] {
        if (buffer) vkDestroyBuffer(dev, buffer, nullptr);
        if (memory) vkFreeMemory(dev, memory, nullptr);
    });
    buffers_.erase(h.id);
}

void VulkanDevice::destroy(rhi::SamplerHandle h) {
    if (!h) return;
    Sampler* s = findSampler(h, "destroy(sampler)", "sampler");
    if (!s) return;
    VkDevice dev = device_;
    VkSampler sampler = s->sampler;
    deferDestroy([dev, sampler] { vkDestroySampler(dev, sampler, nullptr); });
    samplers_.erase(h.id);
}

void VulkanDevice::destroy(rhi::ShaderHandle h) {
    if (!h) return;
    Shader* s = findShader(h, "destroy(shader)", "shader");
    if (!s) return;
    VkDevice dev = device_;
    VkShaderModule module = s->module;
    deferDestroy([dev, module] { vkDestroyShaderModule(dev, module, nullptr); });
    forgetShader(h.id);
    shaders_.erase(h.id);
}

}  // namespace bricklight::vulkan::detail
