// The reflection denoiser (include/bricklight/reflections/denoiser.h): checks, resources and its two passes
// (shaders/reflections/reflection_denoise_{temporal,spatial}.comp). docs/reflections.md.
#include <cmath>
#include <cstring>

#include "bricklight/reflections/denoiser.h"
#include "../common/memory_tally.h"
#include "../common/technique_setup.h"
#include "../common/refusal.h"

namespace bricklight::reflections {

namespace {

// reflection_denoise_params.glsl's Params (std430).
struct ReflectionDenoiseParams {
    glm::mat4 inverseViewProjection, previousViewProjection, previousInverseViewProjection;
    glm::vec4 eye, normalScale, normalOffset;
    glm::uvec4 size, list;
};
static_assert(sizeof(ReflectionDenoiseParams) == 64 * 3 + 16 * 5);

}  // namespace

std::unique_ptr<ReflectionDenoiser> ReflectionDenoiser::create(rhi::IDevice& device, const ReflectionDenoiserDesc& desc, Error* error) {
    const uint32_t width = desc.width, height = desc.height;
    const bricklight::detail::Refusal fail(error, "reflection denoiser");
    if (const std::string problem = detail::sizeProblem(width, height); !problem.empty()) return fail(problem);
    std::unique_ptr<ReflectionDenoiser> d(new ReflectionDenoiser(device));
    d->width_ = width;
    d->height_ = height;
    detail::createShaders(device, shaders::link_bricklight_reflections, {std::pair{"reflections/reflection_denoise_temporal.comp", &d->temporal_},
                                std::pair{"reflections/reflection_denoise_spatial.comp", &d->spatial_},
                                std::pair{"reflections/clear_rgba16f.comp", &d->clear_}});
    rhi::TextureDesc td;
    td.width = width;
    td.height = height;
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    for (int i = 0; i < 2; ++i) {
        td.format = rhi::Format::RGBA16_FLOAT;
        td.debugName = "reflection history " + std::to_string(i);
        d->history_[i] = device.createTexture(td);
        td.format = rhi::Format::R32_FLOAT;
        td.debugName = "reflection history depth " + std::to_string(i);
        d->historyDepth_[i] = device.createTexture(td);
    }
    rhi::BufferDesc bd;
    bd.size = sizeof(ReflectionDenoiseParams);
    bd.usage = rhi::BufferUsage::ShaderRead;
    bd.debugName = "reflection denoiser parameters";
    d->params_ = device.createBuffer(bd);
    rhi::SamplerDesc sampler;
    sampler.minFilter = sampler.magFilter = sampler.mipFilter = rhi::Filter::Nearest;
    sampler.debugName = "reflection denoiser point";
    d->point_ = device.createSampler(sampler);
    if (!d->temporal_ || !d->spatial_ || !d->clear_ || !d->history_[0] || !d->history_[1] || !d->historyDepth_[0] || !d->historyDepth_[1] || !d->params_ || !d->point_)
        return fail("the device could not create the denoiser's histories, parameters or passes (see its messages)", ErrorCode::DeviceFailure);
    return d;
}

ReflectionDenoiser::~ReflectionDenoiser() {
    for (rhi::TextureHandle t : {history_[0], history_[1], historyDepth_[0], historyDepth_[1]})
        if (t) device_.destroy(t);
    if (params_) device_.destroy(params_);
    if (point_) device_.destroy(point_);
    for (rhi::ShaderHandle s : {temporal_, spatial_, clear_})
        if (s) device_.destroy(s);
}

bool ReflectionDenoiser::denoise(const ReflectionDenoiseDesc& d, Error* error) {
    const bricklight::detail::Refusal fail(error, "reflection denoiser");
    // A sampled 2D input of the denoiser's size.
    auto input = [&](rhi::TextureHandle t, const char* name) -> bool {
        const rhi::TextureDesc* td = t ? device_.describe(t) : nullptr;
        if (!td) return fail(std::string(name) + " is missing or not a live texture", ErrorCode::MissingInput);
        if (td->dimension != rhi::TextureDimension::Texture2D || !(td->usage & rhi::TextureUsage::Sampled))
            return fail(std::string(name) + " '" + td->debugName + "' must be a sampled 2D texture", ErrorCode::WrongFormat);
        if (td->width != width_ || td->height != height_)
            return fail(std::string(name) + " '" + td->debugName + "' is " + std::to_string(td->width) + "x" + std::to_string(td->height) +
                        ", the denoiser " + std::to_string(width_) + "x" + std::to_string(height_));
        return true;
    };
    auto buffer = [&](rhi::BufferHandle b, const char* name, uint32_t usage, uint64_t offset, uint64_t bytes) -> bool {
        const rhi::BufferDesc* bd = b ? device_.describe(b) : nullptr;
        if (!bd) return fail(std::string(name) + " is missing or not a live buffer", ErrorCode::MissingInput);
        if (!(bd->usage & usage)) return fail(std::string(name) + " '" + bd->debugName + "' lacks the usage it is bound with", ErrorCode::WrongFormat);
        if (offset % 4 != 0 || offset > bd->size || bd->size - offset < bytes)
            return fail(std::string(name) + " '" + bd->debugName + "' (" + std::to_string(bd->size) + " bytes) does not hold " +
                        std::to_string(bytes) + " bytes at offset " + std::to_string(offset));
        return true;
    };
    if (!buffer(d.tiles, "tiles", rhi::BufferUsage::ShaderRead, 0, 4) ||
        !buffer(d.arguments, "arguments", rhi::BufferUsage::IndirectArgs, d.argumentsOffset, 12) ||
        !buffer(d.count, "count", rhi::BufferUsage::ShaderRead, d.countOffset, 4))
        return false;
    if (!input(d.radiance, "radiance") || !input(d.gbuffer.depth, "depth") || !input(d.gbuffer.normals, "normals") || !input(d.gbuffer.roughness, "roughness")) return false;
    const rhi::TextureDesc* depth = device_.describe(d.gbuffer.depth);
    if (depth->format != rhi::Format::D32_FLOAT && depth->format != rhi::Format::R32_FLOAT)
        return fail("depth '" + depth->debugName + "' must be D32_FLOAT or R32_FLOAT");
    if (d.gbuffer.roughnessChannel >= rhi::formatInfo(device_.describe(d.gbuffer.roughness)->format).channels)
        return fail("roughnessChannel " + std::to_string(d.gbuffer.roughnessChannel) + " is not a channel of the roughness texture");
    const rhi::TextureDesc* out = d.output ? device_.describe(d.output) : nullptr;
    if (!out) return fail("output is missing or not a live texture", ErrorCode::MissingInput);
    if (out->dimension != rhi::TextureDimension::Texture2D || out->format != rhi::Format::RGBA16_FLOAT || !(out->usage & rhi::TextureUsage::Storage))
        return fail("output '" + out->debugName + "' must be a 2D RGBA16_FLOAT texture with Storage usage", ErrorCode::WrongFormat);
    if (out->width != width_ || out->height != height_)
        return fail("output '" + out->debugName + "' is " + std::to_string(out->width) + "x" + std::to_string(out->height) + ", the denoiser " +
                    std::to_string(width_) + "x" + std::to_string(height_));
    for (rhi::TextureHandle in : {d.radiance, d.gbuffer.depth, d.gbuffer.normals, d.gbuffer.roughness})
        if (in == d.output) return fail("output '" + out->debugName + "' is also an input", ErrorCode::Aliasing);
    if (!detail::finite(d.camera.view) || !detail::finite(d.camera.projection) || !detail::finite(d.camera.previousView) || !detail::finite(d.camera.previousProjection) || !detail::finite(d.gbuffer.normalsUnpackScale) ||
        !detail::finite(d.gbuffer.normalsUnpackOffset))
        return fail("the camera matrices and the normals' unpacking must be finite");
    if (d.maxHistory < 1 || d.maxHistory > 256) return fail("maxHistory " + std::to_string(d.maxHistory) + " is outside 1..256");
    // In double: a float inverse of a projection with a far-away far plane loses the depth's precision.
    const glm::dmat4 viewProjection = glm::dmat4(d.camera.projection) * glm::dmat4(d.camera.view);
    const glm::dmat4 previousViewProjection = glm::dmat4(d.camera.previousProjection) * glm::dmat4(d.camera.previousView);
    if (std::abs(glm::determinant(viewProjection)) < 1e-30 || std::abs(glm::determinant(previousViewProjection)) < 1e-30)
        return fail("the camera's view-projection (this frame's or the previous) is not invertible");
    ReflectionDenoiseParams p{};
    p.inverseViewProjection = glm::mat4(glm::inverse(viewProjection));
    p.previousViewProjection = glm::mat4(previousViewProjection);
    p.previousInverseViewProjection = glm::mat4(glm::inverse(previousViewProjection));
    p.eye = glm::vec4(glm::vec3(glm::inverse(glm::dmat4(d.camera.view))[3]), 0.0f);
    p.normalScale = glm::vec4(d.gbuffer.normalsUnpackScale, float(d.maxHistory));
    p.normalOffset = glm::vec4(d.gbuffer.normalsUnpackOffset, 0.0f);
    const bool history = historyValid_ && !d.resetHistory;
    p.size = glm::uvec4(width_, height_, d.gbuffer.roughnessChannel, (d.gbuffer.roughnessPerceptual ? 1u : 0u) | (d.camera.reversedDepth ? 2u : 0u) | (history ? 4u : 0u));
    p.list = glm::uvec4(uint32_t(d.countOffset / 4), 0u, 0u, 0u);
    device_.writeBuffer(params_, 0, &p, sizeof(p));

    const int cur = int(frame_ & 1u), prev = cur ^ 1;
    device_.beginMarker("reflection denoiser");
    // Unlisted pixels hold nothing this frame: their history restarts when their tile is listed again, and the
    // composite keeps the GI's specular there.
    device_.beginMarker("clears");
    for (rhi::TextureHandle t : {history_[cur], d.output}) {
        rhi::DispatchState s;
        s.shader = clear_;
        s.label = "reflection denoise clear";
        s.bindings.storageImages.push(rhi::storageImage(0, t, rhi::Access::Write, 0));
        device_.dispatch(s, (width_ + 15) / 16, (height_ + 15) / 16, 1);
    }
    device_.endMarker();
    device_.beginMarker("temporal");
    {
        rhi::DispatchState s;
        s.shader = temporal_;
        s.label = "reflection denoise temporal";
        s.bindings.readBuffers.push({0, params_, {}});
        s.bindings.readBuffers.push({1, d.tiles, {}});
        s.bindings.readBuffers.push({2, d.count, {}});
        s.bindings.textures.push({0, rhi::wholeTexture(d.radiance), point_});
        s.bindings.textures.push({1, rhi::wholeTexture(d.gbuffer.depth), point_});
        s.bindings.textures.push({2, rhi::wholeTexture(d.gbuffer.roughness), point_});
        s.bindings.textures.push({3, rhi::wholeTexture(history_[prev]), point_});
        s.bindings.textures.push({4, rhi::wholeTexture(historyDepth_[prev]), point_});
        s.bindings.storageImages.push(rhi::storageImage(0, history_[cur], rhi::Access::Write, 0));
        s.bindings.storageImages.push(rhi::storageImage(1, historyDepth_[cur], rhi::Access::Write, 0));
        device_.dispatchIndirect(s, d.arguments, d.argumentsOffset);
    }
    device_.endMarker();
    device_.beginMarker("spatial");
    {
        rhi::DispatchState s;
        s.shader = spatial_;
        s.label = "reflection denoise spatial";
        s.bindings.readBuffers.push({0, params_, {}});
        s.bindings.readBuffers.push({1, d.tiles, {}});
        s.bindings.readBuffers.push({2, d.count, {}});
        s.bindings.textures.push({0, rhi::wholeTexture(history_[cur]), point_});
        s.bindings.textures.push({1, rhi::wholeTexture(d.gbuffer.depth), point_});
        s.bindings.textures.push({2, rhi::wholeTexture(d.gbuffer.normals), point_});
        s.bindings.textures.push({3, rhi::wholeTexture(d.gbuffer.roughness), point_});
        s.bindings.storageImages.push(rhi::storageImage(0, d.output, rhi::Access::Write, 0));
        device_.dispatchIndirect(s, d.arguments, d.argumentsOffset);
    }
    device_.endMarker();
    device_.endMarker();
    ++frame_;
    historyValid_ = true;
    return true;
}

MemoryUse ReflectionDenoiser::memoryUse() const { return detail::MemoryTally(device_).add(params_).add(history_[0]).add(history_[1]).add(historyDepth_[0]).add(historyDepth_[1]).use(); }

}  // namespace bricklight::reflections
