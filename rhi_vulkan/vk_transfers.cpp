// Transfers: write/copy/clear, and blocking read-backs. Uploads are staged through the frame's upload
// ring; read-backs through a host-visible buffer of their own that is freed right after the wait.
#include <algorithm>
#include <cstring>

#include "vk_device.h"
#include "vk_formats.h"

namespace bricklight::vulkan::detail {

namespace {
VkDeviceSize align16(VkDeviceSize v) { return (v + 15) / 16 * 16; }

AccessRequest transferRequest(bool write, VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED) {
    AccessRequest r;
    r.stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    r.access = write ? VK_ACCESS_2_TRANSFER_WRITE_BIT : VK_ACCESS_2_TRANSFER_READ_BIT;
    r.layout = layout;
    r.write = write;
    r.shaderWriteOnly = false;
    return r;
}
}  // namespace

void VulkanDevice::trackTransfer(VkCommandBuffer c, CallPlan& plan) { recordBarriers(c, plan); }

bool VulkanDevice::checkSubresource(const Texture& t, rhi::TextureSubresource sub, const std::string& call,
                                    uint32_t* layers) {
    const rhi::TextureDesc& d = t.desc;
    if (sub.mip >= d.mipLevels)
        return fail(call + ": mip " + std::to_string(sub.mip) + " is outside " + textureName(t) + " (" +
                    std::to_string(d.mipLevels) + " mips)");
    if (d.dimension == rhi::TextureDimension::Texture3D) return *layers = 1, true;
    if (sub.layer >= t.layers || (sub.layerCount && sub.layerCount > t.layers - sub.layer))
        return fail(call + ": layers [" + std::to_string(sub.layer) + ", +" + std::to_string(sub.layerCount) +
                    ") are outside " + textureName(t) + " (" + std::to_string(t.layers) + " layers)");
    *layers = sub.layerCount ? sub.layerCount : t.layers - sub.layer;
    return true;
}

void VulkanDevice::copyTextureRegions(VkCommandBuffer c, Texture& t, uint32_t mip, uint32_t layer, uint32_t layers,
                                      VkBuffer buffer, VkDeviceSize offset, bool toImage, VkDeviceSize* layerStride) {
    // One region per layer at a 16-byte aligned offset (bufferOffset alignment); tight rows.
    const rhi::TextureDesc& d = t.desc;
    VkExtent3D extent{rhi::mipExtent(d.width, mip), rhi::mipExtent(d.height, mip), rhi::textureDepth(d, mip)};
    const VkDeviceSize layerBytes =
        VkDeviceSize(extent.width) * extent.height * extent.depth * rhi::formatInfo(d.format).bytesPerTexel;
    *layerStride = align16(layerBytes);
    std::vector<VkBufferImageCopy> regions;
    for (uint32_t l = 0; l < layers; ++l) {
        VkBufferImageCopy r{};
        r.bufferOffset = offset + l * *layerStride;
        r.imageSubresource = {t.aspect, mip, layer + l, 1};
        r.imageExtent = extent;
        regions.push_back(r);
    }
    if (toImage)
        vkCmdCopyBufferToImage(c, buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()),
                               regions.data());
    else
        vkCmdCopyImageToBuffer(c, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, uint32_t(regions.size()),
                               regions.data());
}

bool VulkanDevice::writeBuffer(rhi::BufferHandle h, uint64_t offset, const void* data, uint64_t size) {
    const std::string call = "writeBuffer";
    Buffer* b = findBuffer(h, call, "buffer");
    if (!b) return false;
    const std::string where = call + " " + bufferName(*b);
    if (!data || !size) return fail(where + ": data is null or size is 0");
    if (offset > b->desc.size || size > b->desc.size - offset)
        return fail(where + ": [" + std::to_string(offset) + ", +" + std::to_string(size) + ") is outside the buffer (" +
                    std::to_string(b->desc.size) + " bytes)");
    UploadAllocation up = allocateUpload(size, 16);
    if (!up.buffer) return fail(where + ": out of host memory for staging");
    memcpy(up.mapped, data, size);
    CallPlan plan;
    addBufferUse(plan, *b, transferRequest(true));
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    VkBufferCopy region{up.offset, offset, size};
    vkCmdCopyBuffer(c, up.buffer, b->buffer, 1, &region);
    releaseWrapped(c, plan);
    return true;
}

bool VulkanDevice::writeTexture(rhi::TextureHandle h, rhi::TextureSubresource sub, const void* data) {
    const std::string call = "writeTexture";
    Texture* t = findTexture(h, call, "texture");
    if (!t) return false;
    const std::string where = call + " " + textureName(*t);
    if (!data) return fail(where + ": data is null");
    uint32_t layers;
    if (!checkSubresource(*t, sub, where, &layers)) return false;
    const uint32_t layer = t->desc.dimension == rhi::TextureDimension::Texture3D ? 0 : sub.layer;
    rhi::TextureSubresource one{sub.mip, layer, 1};
    const VkDeviceSize layerBytes = rhi::subresourceBytes(t->desc, one);
    UploadAllocation up = allocateUpload(align16(layerBytes) * layers, 16);
    if (!up.buffer) return fail(where + ": out of host memory for staging");
    for (uint32_t l = 0; l < layers; ++l)
        memcpy(up.mapped + l * align16(layerBytes), static_cast<const uint8_t*>(data) + l * layerBytes, layerBytes);
    CallPlan plan;
    addTextureUse(plan, *t, sub.mip, 1, layer, layers, transferRequest(true, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL), where,
                  "texture");
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    VkDeviceSize stride;
    copyTextureRegions(c, *t, sub.mip, layer, layers, up.buffer, up.offset, true, &stride);
    releaseWrapped(c, plan);
    return true;
}

bool VulkanDevice::copyBuffer(rhi::BufferHandle dstH, uint64_t dstOffset, rhi::BufferHandle srcH, uint64_t srcOffset,
                              uint64_t size) {
    const std::string call = "copyBuffer";
    Buffer* dst = findBuffer(dstH, call, "dst");
    Buffer* src = dst ? findBuffer(srcH, call, "src") : nullptr;
    if (!dst || !src) return false;
    const std::string where = call + " " + bufferName(*src) + " -> " + bufferName(*dst);
    if (!size) return fail(where + ": size is 0");
    if (srcOffset > src->desc.size || size > src->desc.size - srcOffset)
        return fail(where + ": source range [" + std::to_string(srcOffset) + ", +" + std::to_string(size) +
                    ") is outside the buffer");
    if (dstOffset > dst->desc.size || size > dst->desc.size - dstOffset)
        return fail(where + ": destination range [" + std::to_string(dstOffset) + ", +" + std::to_string(size) +
                    ") is outside the buffer");
    if (src == dst && srcOffset < dstOffset + size && dstOffset < srcOffset + size)
        return fail(where + ": source and destination ranges overlap");
    CallPlan plan;
    addBufferUse(plan, *src, transferRequest(false));
    addBufferUse(plan, *dst, transferRequest(true));
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    VkBufferCopy region{srcOffset, dstOffset, size};
    vkCmdCopyBuffer(c, src->buffer, dst->buffer, 1, &region);
    releaseWrapped(c, plan);
    return true;
}

bool VulkanDevice::copyTexture(rhi::TextureHandle dstH, rhi::TextureSubresource dstSub, rhi::TextureHandle srcH,
                               rhi::TextureSubresource srcSub) {
    const std::string call = "copyTexture";
    Texture* dst = findTexture(dstH, call, "dst");
    Texture* src = dst ? findTexture(srcH, call, "src") : nullptr;
    if (!dst || !src) return false;
    const std::string where = call + " " + textureName(*src) + " -> " + textureName(*dst);
    uint32_t srcLayers, dstLayers;
    if (!checkSubresource(*src, srcSub, where + " (src)", &srcLayers) ||
        !checkSubresource(*dst, dstSub, where + " (dst)", &dstLayers))
        return false;
    if (src->desc.format != dst->desc.format)
        return fail(where + ": formats differ (" + rhi::formatName(src->desc.format) + " vs " +
                    rhi::formatName(dst->desc.format) + ")");
    const VkExtent3D extent{rhi::mipExtent(src->desc.width, srcSub.mip), rhi::mipExtent(src->desc.height, srcSub.mip),
                            rhi::textureDepth(src->desc, srcSub.mip)};
    if (extent.width != rhi::mipExtent(dst->desc.width, dstSub.mip) ||
        extent.height != rhi::mipExtent(dst->desc.height, dstSub.mip) ||
        extent.depth != rhi::textureDepth(dst->desc, dstSub.mip) || srcLayers != dstLayers ||
        (src->desc.dimension == rhi::TextureDimension::Texture3D) != (dst->desc.dimension == rhi::TextureDimension::Texture3D))
        return fail(where + ": the subresources differ in size or layer count");
    const bool is3D = src->desc.dimension == rhi::TextureDimension::Texture3D;
    const uint32_t srcLayer = is3D ? 0 : srcSub.layer, dstLayer = is3D ? 0 : dstSub.layer;
    if (src == dst && srcSub.mip == dstSub.mip && srcLayer < dstLayer + dstLayers && dstLayer < srcLayer + srcLayers)
        return fail(where + ": source and destination subresources overlap");
    CallPlan plan;
    addTextureUse(plan, *src, srcSub.mip, 1, srcLayer, srcLayers,
                  transferRequest(false, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL), where, "src");
    addTextureUse(plan, *dst, dstSub.mip, 1, dstLayer, dstLayers,
                  transferRequest(true, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL), where, "dst");
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    VkImageCopy region{};
    region.srcSubresource = {src->aspect, srcSub.mip, srcLayer, srcLayers};
    region.dstSubresource = {dst->aspect, dstSub.mip, dstLayer, dstLayers};
    region.extent = extent;
    vkCmdCopyImage(c, src->image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                   &region);
    releaseWrapped(c, plan);
    return true;
}

bool VulkanDevice::clearBuffer(rhi::BufferHandle h, rhi::BufferRange range, uint32_t value) {
    const std::string call = "clearBuffer";
    Buffer* b = findBuffer(h, call, "buffer");
    if (!b) return false;
    const std::string where = call + " " + bufferName(*b);
    if (range.offset % 4 || range.size % 4)
        return fail(where + ": offset and size must be multiples of 4 (" + std::to_string(range.offset) + ", " +
                    std::to_string(range.size) + ")");
    if (range.offset >= b->desc.size || (range.size && range.size > b->desc.size - range.offset))
        return fail(where + ": range [" + std::to_string(range.offset) + ", +" + std::to_string(range.size) +
                    ") is outside the buffer (" + std::to_string(b->desc.size) + " bytes)");
    CallPlan plan;
    addBufferUse(plan, *b, transferRequest(true));
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    // Size 0 = to the end; the VkBuffer is padded to a multiple of 4 so VK_WHOLE_SIZE covers every byte.
    vkCmdFillBuffer(c, b->buffer, range.offset, range.size ? range.size : VK_WHOLE_SIZE, value);
    releaseWrapped(c, plan);
    return true;
}

bool VulkanDevice::clearTexture(rhi::TextureHandle h, uint32_t baseMip, uint32_t mipCount, rhi::ClearValue value) {
    const std::string call = "clearTexture";
    Texture* t = findTexture(h, call, "texture");
    if (!t) return false;
    const std::string where = call + " " + textureName(*t);
    if (baseMip >= t->desc.mipLevels || (mipCount && mipCount > t->desc.mipLevels - baseMip))
        return fail(where + ": mips [" + std::to_string(baseMip) + ", +" + std::to_string(mipCount) + ") are outside the " +
                    std::to_string(t->desc.mipLevels) + " mips of the texture");
    const uint32_t mips = mipCount ? mipCount : t->desc.mipLevels - baseMip;
    CallPlan plan;
    addTextureUse(plan, *t, baseMip, mips, 0, t->layers, transferRequest(true, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL),
                  where, "texture");
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    VkImageSubresourceRange range{t->aspect, baseMip, mips, 0, t->layers};
    if (isDepthFormat(t->desc.format)) {
        VkClearDepthStencilValue v{value.f[0], 0};
        vkCmdClearDepthStencilImage(c, t->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
    } else {
        // Float formats take value.f, integer formats value.u (the union gives sint its bits unchanged).
        VkClearColorValue v;
        memcpy(&v, &value, sizeof(v));
        vkCmdClearColorImage(c, t->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &v, 1, &range);
    }
    releaseWrapped(c, plan);
    return true;
}

bool VulkanDevice::readBuffer(rhi::BufferHandle h, uint64_t offset, uint64_t size, void* out) {
    const std::string call = "readBuffer";
    Buffer* b = findBuffer(h, call, "buffer");
    if (!b) return false;
    const std::string where = call + " " + bufferName(*b);
    if (appCommandBuffer_)
        return fail(where + ": not available while recording into an application command buffer "
                            "(submit it, then setCommandBuffer(VK_NULL_HANDLE))");
    if (!out || !size) return fail(where + ": out is null or size is 0");
    if (offset > b->desc.size || size > b->desc.size - offset)
        return fail(where + ": [" + std::to_string(offset) + ", +" + std::to_string(size) + ") is outside the buffer (" +
                    std::to_string(b->desc.size) + " bytes)");
    VkBuffer staging;
    VkDeviceMemory memory;
    void* mapped;
    if (!allocateBuffer(size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                        VK_MEMORY_PROPERTY_HOST_CACHED_BIT, &staging, &memory, &mapped))
        return fail(where + ": cannot allocate " + std::to_string(size) + " bytes of read-back memory");
    CallPlan plan;
    addBufferUse(plan, *b, transferRequest(false));
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    VkBufferCopy region{offset, 0, size};
    vkCmdCopyBuffer(c, b->buffer, staging, 1, &region);
    BarrierBatch host;  // the copy's writes must be visible to the host after the wait
    host.memory(VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                VK_ACCESS_2_HOST_READ_BIT);
    barrierCount_ += host.flush(c);
    releaseWrapped(c, plan);
    const bool ok = waitForGpu();
    if (ok) memcpy(out, mapped, size);
    vkDestroyBuffer(device_, staging, nullptr);
    vkFreeMemory(device_, memory, nullptr);
    return ok;
}

uint64_t VulkanDevice::requestReadback(rhi::BufferHandle h, uint64_t offset, uint64_t size) {
    const std::string call = "requestReadback";
    Buffer* b = findBuffer(h, call, "buffer");
    if (!b) return 0;
    const std::string where = call + " " + bufferName(*b);
    if (!size) return fail(where + ": size is 0"), 0;
    if (offset > b->desc.size || size > b->desc.size - offset)
        return fail(where + ": [" + std::to_string(offset) + ", +" + std::to_string(size) + ") is outside the buffer (" +
                    std::to_string(b->desc.size) + " bytes)"),
               0;
    PendingReadback rb;
    if (!allocateBuffer(size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                        VK_MEMORY_PROPERTY_HOST_CACHED_BIT, &rb.buffer, &rb.memory, &rb.mapped))
        return fail(where + ": cannot allocate " + std::to_string(size) + " bytes of read-back memory"), 0;
    CallPlan plan;
    addBufferUse(plan, *b, transferRequest(false));
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    VkBufferCopy region{offset, 0, size};
    vkCmdCopyBuffer(c, b->buffer, rb.buffer, 1, &region);
    BarrierBatch host;
    host.memory(VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                VK_ACCESS_2_HOST_READ_BIT);
    barrierCount_ += host.flush(c);
    releaseWrapped(c, plan);
    rb.size = size;
    rb.serial = frameSerial_;
    rb.waitCount = waitCount_;
    const uint64_t ticket = nextReadbackTicket_++;
    readbacks_[ticket] = rb;
    return ticket;
}

rhi::ReadbackStatus VulkanDevice::pollReadback(uint64_t ticket, void* out) {
    auto it = readbacks_.find(ticket);
    if (it == readbacks_.end()) return rhi::ReadbackStatus::Failed;  // the status is the message
    for (FrameSlot& f : frames_)
        if (f.pending && vkGetFenceStatus(device_, f.fence) == VK_SUCCESS) recycle(f, true);
    PendingReadback& rb = it->second;
    if (int64_t(rb.serial) > completedSerial_ && rb.waitCount == waitCount_) return rhi::ReadbackStatus::Pending;
    if (out) memcpy(out, rb.mapped, rb.size);
    vkDestroyBuffer(device_, rb.buffer, nullptr);
    vkFreeMemory(device_, rb.memory, nullptr);
    readbacks_.erase(it);
    return rhi::ReadbackStatus::Ready;
}

bool VulkanDevice::readTexture(rhi::TextureHandle h, rhi::TextureSubresource sub, void* out) {
    const std::string call = "readTexture";
    Texture* t = findTexture(h, call, "texture");
    if (!t) return false;
    const std::string where = call + " " + textureName(*t);
    if (appCommandBuffer_)
        return fail(where + ": not available while recording into an application command buffer "
                            "(submit it, then setCommandBuffer(VK_NULL_HANDLE))");
    if (!out) return fail(where + ": out is null");
    uint32_t layers;
    if (!checkSubresource(*t, sub, where, &layers)) return false;
    const uint32_t layer = t->desc.dimension == rhi::TextureDimension::Texture3D ? 0 : sub.layer;
    const VkDeviceSize layerBytes = rhi::subresourceBytes(t->desc, {sub.mip, layer, 1});
    VkBuffer staging;
    VkDeviceMemory memory;
    void* mapped;
    if (!allocateBuffer(align16(layerBytes) * layers, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                        VK_MEMORY_PROPERTY_HOST_CACHED_BIT, &staging, &memory, &mapped))
        return fail(where + ": cannot allocate read-back memory");
    CallPlan plan;
    addTextureUse(plan, *t, sub.mip, 1, layer, layers, transferRequest(false, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL), where,
                  "texture");
    VkCommandBuffer c = cmd();
    trackTransfer(c, plan);
    VkDeviceSize stride;
    copyTextureRegions(c, *t, sub.mip, layer, layers, staging, 0, false, &stride);
    BarrierBatch host;
    host.memory(VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                VK_ACCESS_2_HOST_READ_BIT);
    barrierCount_ += host.flush(c);
    releaseWrapped(c, plan);
    const bool ok = waitForGpu();
    if (ok)
        for (uint32_t l = 0; l < layers; ++l)
            memcpy(static_cast<uint8_t*>(out) + l * layerBytes, static_cast<uint8_t*>(mapped) + l * stride, layerBytes);
    vkDestroyBuffer(device_, staging, nullptr);
    vkFreeMemory(device_, memory, nullptr);
    return ok;
}

}  // namespace bricklight::vulkan::detail
