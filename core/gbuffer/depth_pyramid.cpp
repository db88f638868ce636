// The depth pyramid's passes: a copy of the depth into mip 0, then one reduction per mip
// (shaders/gbuffer/depth_pyramid_*.comp). docs/gbuffer.md.
#include "bricklight/gbuffer/depth_pyramid.h"

#include <algorithm>

#include "../common/memory_tally.h"
#include "../common/technique_setup.h"
#include "../common/refusal.h"

namespace bricklight::gbuffer {

namespace {

struct Size {
    uint32_t v[4];  // uvec4 size in both passes
};

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
    detail::createShaders(device, shaders::link_bricklight_gbuffer, {{"gbuffer/depth_pyramid_copy.comp", &p->copy_}, {"gbuffer/depth_pyramid_reduce.comp", &p->reduce_}});
    rhi::TextureDesc td;
    td.format = rhi::Format::RG32_FLOAT;
    td.width = width;
    td.height = height;
    td.mipLevels = p->mipCount_;
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = "depth pyramid";
    p->texture_ = device.createTexture(td);
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "depth pyramid point";
    p->point_ = device.createSampler(sd);
    if (!p->copy_ || !p->reduce_ || !p->texture_ || !p->point_)
        return fail("the device could not create the pyramid's texture, sampler or shaders (see its messages)", ErrorCode::DeviceFailure);
    return p;
}

DepthPyramid::~DepthPyramid() {
    if (texture_) device_.destroy(texture_);
    if (point_) device_.destroy(point_);
    for (rhi::ShaderHandle s : {copy_, reduce_})
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
    {
        const Size size{{width_, height_, 0, 0}};
        rhi::DispatchState s;
        s.shader = copy_;
        s.label = "depth pyramid copy";
        s.bindings.constants.push(rhi::constants(0, size));
        rhi::TextureView source = rhi::textureMip(depth, 0);
        s.bindings.textures.push({0, source, point_});
        s.bindings.storageImages.push(rhi::storageImage(0, texture_, rhi::Access::Write, 0));
        device_.dispatch(s, (width_ + 7) / 8, (height_ + 7) / 8, 1);
    }
    for (uint32_t m = 1; m < mipCount_; ++m) {
        const Size size{{rhi::mipExtent(width_, m - 1), rhi::mipExtent(height_, m - 1), rhi::mipExtent(width_, m),
                         rhi::mipExtent(height_, m)}};
        rhi::DispatchState s;
        s.shader = reduce_;
        s.label = "depth pyramid reduce";
        s.bindings.constants.push(rhi::constants(0, size));
        s.bindings.storageImages.push(rhi::storageImage(0, texture_, rhi::Access::Read, uint8_t(m - 1)));
        s.bindings.storageImages.push(rhi::storageImage(1, texture_, rhi::Access::Write, uint8_t(m)));
        device_.dispatch(s, (size.v[2] + 7) / 8, (size.v[3] + 7) / 8, 1);
    }
    device_.endMarker();
    return true;
}

MemoryUse DepthPyramid::memoryUse() const { return detail::MemoryTally(device_).add(texture_).use(); }

}  // namespace bricklight::gbuffer
