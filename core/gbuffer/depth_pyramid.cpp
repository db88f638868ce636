// The depth pyramid's passes: mip 0 and the next five mips from the depth texture in one dispatch, then five more
// mips a dispatch from the last one written (shaders/gbuffer/depth_pyramid_{first,next}.comp). docs/gbuffer.md.
#include "bricklight/gbuffer/depth_pyramid.h"

#include <algorithm>

#include "../common/memory_tally.h"
#include "../common/technique_setup.h"
#include "../common/refusal.h"

namespace bricklight::gbuffer {

namespace {

struct Size {
    uint32_t v[4];  // uvec4 size: mip s's extent, the mips written after it
};

constexpr uint32_t kMipsPerDispatch = 5;  // depth_pyramid_tiles_body.glsl: 32 × 32 texels of mip s a group

}  // namespace

uint32_t depthPyramidMipCount(uint32_t width, uint32_t height) {
    uint32_t m = std::max(width, height), count = 1;
    while (m > 1) {
        m >>= 1;
        ++count;
    }
    return count;
}

std::unique_ptr<DepthPyramid> DepthPyramid::create(rhi::IDevice& device, const DepthPyramidDesc& desc, Error* error) {
    const uint32_t width = desc.width, height = desc.height;
    const bricklight::detail::Refusal fail(error, "depth pyramid");
    const uint32_t limit = std::min(detail::kMaxSize, device.capabilities().limits.maxTextureSize2D);
    if (width == 0 || height == 0 || width > limit || height > limit)
        return fail("size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." + std::to_string(limit) +
                    " on each side", ErrorCode::WrongSize);
    if (!device.capabilities().supports(rhi::Format::RG32_FLOAT, rhi::FormatSupport::Storage | rhi::FormatSupport::Sampled))
        return fail("the device cannot use RG32_FLOAT as a storage image", ErrorCode::Unsupported);
    std::unique_ptr<DepthPyramid> p(new DepthPyramid(device));
    p->width_ = width;
    p->height_ = height;
    p->mipCount_ = depthPyramidMipCount(width, height);
    detail::createShaders(device, shaders::link_bricklight_gbuffer, {{"gbuffer/depth_pyramid_first.comp", &p->first_}, {"gbuffer/depth_pyramid_next.comp", &p->next_}});
    rhi::TextureDesc td;
    td.format = rhi::Format::RG32_FLOAT;
    td.width = width;
    td.height = height;
    td.mipLevels = p->mipCount_;
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = "depth pyramid";
    p->texture_ = device.createTexture(td);
    // What a dispatch's unused mip slots bind past the end of the chain (never written): one mip per slot, so that
    // no two write bindings share a subresource.
    td.width = td.height = 32;
    td.mipLevels = kMipsPerDispatch + 1;
    td.usage = rhi::TextureUsage::Storage;
    td.debugName = "depth pyramid unused mip slots";
    p->unusedMips_ = device.createTexture(td);
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "depth pyramid point";
    p->point_ = device.createSampler(sd);
    if (!p->first_ || !p->next_ || !p->texture_ || !p->unusedMips_ || !p->point_)
        return fail("the device could not create the pyramid's texture, sampler or shaders (see its messages)", ErrorCode::DeviceFailure);
    return p;
}

DepthPyramid::~DepthPyramid() {
    for (rhi::TextureHandle t : {texture_, unusedMips_})
        if (t) device_.destroy(t);
    if (point_) device_.destroy(point_);
    for (rhi::ShaderHandle s : {first_, next_})
        if (s) device_.destroy(s);
}

bool DepthPyramid::build(rhi::TextureHandle depth, Error* error) {
    const bricklight::detail::Refusal fail(error, "depth pyramid");
    const rhi::TextureDesc* d = depth ? device_.describe(depth) : nullptr;
    if (!d) return fail("the depth texture is null or destroyed", ErrorCode::InvalidHandle);
    const std::string name = d->debugName.empty() ? std::string("the depth texture") : "depth texture '" + d->debugName + "'";
    if (d->dimension != rhi::TextureDimension::Texture2D)
        return fail(name + " is a " + rhi::textureDimensionName(d->dimension) + ", not a 2D texture", ErrorCode::WrongFormat);
    if (d->format != rhi::Format::D32_FLOAT && d->format != rhi::Format::R32_FLOAT)
        return fail(name + " has format " + rhi::formatName(d->format) + " (expected D32_FLOAT or R32_FLOAT)", ErrorCode::WrongFormat);
    if (!(d->usage & rhi::TextureUsage::Sampled)) return fail(name + " lacks Sampled usage", ErrorCode::WrongFormat);
    if (d->width != width_ || d->height != height_)
        return fail(name + " is " + std::to_string(d->width) + "x" + std::to_string(d->height) + ", the pyramid " +
                    std::to_string(width_) + "x" + std::to_string(height_));
    device_.beginMarker("depth pyramid");
    for (uint32_t from = 0;;) {
        const uint32_t mips = std::min(kMipsPerDispatch, mipCount_ - 1 - from);
        const uint32_t w = rhi::mipExtent(width_, from), h = rhi::mipExtent(height_, from);
        rhi::DispatchState s;
        s.shader = from == 0 ? first_ : next_;
        s.label = from == 0 ? "depth pyramid mips 0-5" : "depth pyramid next mips";
        const Size size{{w, h, mips, 0}};
        s.bindings.constants.push(rhi::constants(0, size));
        if (from == 0) {
            s.bindings.textures.push({0, rhi::textureMip(depth, 0), point_});
            s.bindings.storageImages.push(rhi::storageImage(0, texture_, rhi::Access::Write, 0));
        } else {
            s.bindings.storageImages.push(rhi::storageImage(0, texture_, rhi::Access::Read, uint8_t(from)));
        }
        for (uint32_t j = 1; j <= kMipsPerDispatch; ++j)
            s.bindings.storageImages.push(j <= mips ? rhi::storageImage(j, texture_, rhi::Access::Write, uint8_t(from + j))
                                                    : rhi::storageImage(j, unusedMips_, rhi::Access::Write, uint8_t(j)));
        // A group per 32 × 32 texels of mip `from`; the last in a row (column) takes the remainder.
        device_.dispatch(s, std::max(w >> 5, 1u), std::max(h >> 5, 1u), 1);
        from += mips;
        if (mips == 0 || from + 1 >= mipCount_) break;
    }
    device_.endMarker();
    return true;
}

MemoryUse DepthPyramid::memoryUse() const { return detail::MemoryTally(device_).add(texture_).add(unusedMips_).use(); }

}  // namespace bricklight::gbuffer
