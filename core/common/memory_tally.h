// A technique's memoryUse(): its live textures (every mip and layer) and buffers, named by their debug names.
#pragma once

#include "bricklight/memory_use.h"
#include "bricklight/rhi.h"

namespace bricklight::detail {

class MemoryTally {
public:
    explicit MemoryTally(const rhi::IDevice& device) : device_(device) {}
    MemoryTally& add(rhi::TextureHandle texture) {
        if (const rhi::TextureDesc* d = texture ? device_.describe(texture) : nullptr) {
            uint64_t bytes = 0;
            for (uint32_t mip = 0; mip < d->mipLevels; ++mip) bytes += rhi::subresourceBytes(*d, {mip, 0, 0});
            push(d->debugName, bytes);
        }
        return *this;
    }
    MemoryTally& add(rhi::BufferHandle buffer) {
        if (const rhi::BufferDesc* d = buffer ? device_.describe(buffer) : nullptr) push(d->debugName, d->size);
        return *this;
    }
    const MemoryUse& use() const { return use_; }

private:
    void push(const std::string& name, uint64_t bytes) {
        use_.resources.push_back({name, bytes});
        use_.totalBytes += bytes;
    }
    const rhi::IDevice& device_;
    MemoryUse use_;
};

}  // namespace bricklight::detail
