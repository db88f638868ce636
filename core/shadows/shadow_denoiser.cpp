// The shadow denoiser (include/bricklight/shadows/denoiser.h): checks, resources and the records of its temporal,
// decided and filter passes (shaders/shadows/denoise_shadows_*.comp). docs/shadows.md.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "bricklight/shadows/denoiser.h"
#include "../common/memory_tally.h"
#include "../common/technique_setup.h"
#include "../common/refusal.h"

namespace bricklight::shadows {

namespace {

// The passes' parameters (the Params block of denoise_shadows_common.glsl, std430).
struct ShadowDenoiseParams {
    glm::mat4 inverseViewProjection, previousViewProjection, inversePreviousViewProjection;
    glm::vec4 eye, normalScale, normalBias;
    glm::uvec4 size, options;
};
static_assert(sizeof(ShadowDenoiseParams) == 272);

}  // namespace

std::unique_ptr<ShadowDenoiser> ShadowDenoiser::create(rhi::IDevice& device, const ShadowDenoiserDesc& desc, Error* error) {
    const uint32_t width = desc.width, height = desc.height;
    const bricklight::detail::Refusal fail(error, "shadow denoiser");
    if (const std::string problem = detail::sizeProblem(width, height); !problem.empty()) return fail(problem);
    std::unique_ptr<ShadowDenoiser> d(new ShadowDenoiser(device));
    d->width_ = width;
    d->height_ = height;
    detail::createShaders(device, shaders::link_bricklight_shadows, {std::pair{"shadows/denoise_shadows_temporal.comp", &d->temporal_}, std::pair{"shadows/denoise_shadows_decided.comp", &d->decided_},
                                std::pair{"shadows/denoise_shadows_filter.comp", &d->filter_}});
    rhi::TextureDesc td;
    td.width = width;
    td.height = height;
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    const char* historyNames[2] = {"shadow denoiser history 0", "shadow denoiser history 1"};
    const char* geometryNames[2] = {"shadow denoiser geometry 0", "shadow denoiser geometry 1"};
    const char* filterNames[2] = {"shadow denoiser filter 0", "shadow denoiser filter 1"};
    for (int i = 0; i < 2; ++i) {
        td.format = rhi::Format::RGBA16_FLOAT;
        td.debugName = historyNames[i];
        d->history_[i] = device.createTexture(td);
        td.format = rhi::Format::RG32_UINT;
        td.debugName = geometryNames[i];
        d->geometry_[i] = device.createTexture(td);
        td.format = rhi::Format::R16_FLOAT;
        td.debugName = filterNames[i];
        d->filtered_[i] = device.createTexture(td);
    }
    td.format = rhi::Format::R32_UINT;
    td.width = (width + kShadowTileWidth - 1) / kShadowTileWidth;
    td.height = (height + kShadowTileHeight - 1) / kShadowTileHeight;
    td.usage = rhi::TextureUsage::Storage;
    td.debugName = "shadow denoiser tiles";
    d->listed_ = device.createTexture(td);
    rhi::BufferDesc bd;
    bd.size = sizeof(ShadowDenoiseParams);
    bd.usage = rhi::BufferUsage::ShaderRead;
    bd.debugName = "shadow denoiser parameters";
    d->params_ = device.createBuffer(bd);
    rhi::SamplerDesc sampler;
    sampler.minFilter = sampler.magFilter = sampler.mipFilter = rhi::Filter::Nearest;
    sampler.debugName = "shadow denoiser point";
    d->point_ = device.createSampler(sampler);
    bool ok = d->temporal_ && d->decided_ && d->filter_ && d->listed_ && d->params_ && d->point_;
    for (int i = 0; i < 2; ++i) ok = ok && d->history_[i] && d->geometry_[i] && d->filtered_[i];
    if (!ok) return fail("the device could not create the denoiser's textures, buffer or passes (see its messages)", ErrorCode::DeviceFailure);
    return d;
}

ShadowDenoiser::~ShadowDenoiser() {
    for (int i = 0; i < 2; ++i)
        for (rhi::TextureHandle t : {history_[i], geometry_[i], filtered_[i]})
            if (t) device_.destroy(t);
    if (listed_) device_.destroy(listed_);
    if (params_) device_.destroy(params_);
    if (point_) device_.destroy(point_);
    for (rhi::ShaderHandle s : {temporal_, decided_, filter_})
        if (s) device_.destroy(s);
}

bool ShadowDenoiser::denoise(const ShadowClassifier& classifier, const ShadowDenoiseDesc& d, Error* error) {
    const bricklight::detail::Refusal fail(error, "shadow denoiser");
    const std::string size = std::to_string(width_) + "x" + std::to_string(height_);
    if (classifier.width() != width_ || classifier.height() != height_)
        return fail("the shadow classifier is " + std::to_string(classifier.width()) + "x" + std::to_string(classifier.height()) + ", the denoiser " + size);
    auto check = [&](rhi::TextureHandle t, const char* name, bool depth) -> bool {
        const rhi::TextureDesc* td = t ? device_.describe(t) : nullptr;
        if (!td) return fail(std::string(name) + " is missing or not a live texture", ErrorCode::MissingInput);
        if (td->dimension != rhi::TextureDimension::Texture2D || !(td->usage & rhi::TextureUsage::Sampled))
            return fail(std::string(name) + " '" + td->debugName + "' must be a sampled 2D texture", ErrorCode::WrongFormat);
        if (depth && td->format != rhi::Format::D32_FLOAT && td->format != rhi::Format::R32_FLOAT)
            return fail(std::string(name) + " '" + td->debugName + "' must be D32_FLOAT or R32_FLOAT");
        if (td->width != width_ || td->height != height_)
            return fail(std::string(name) + " '" + td->debugName + "' is " + std::to_string(td->width) + "x" + std::to_string(td->height) + ", the denoiser " + size);
        return true;
    };
    if (!check(d.gbuffer.depth, "depth", true) || !check(d.gbuffer.normals, "normals", false)) return false;
    const rhi::TextureDesc* out = d.output ? device_.describe(d.output) : nullptr;
    if (!out) return fail("output is missing or not a live texture", ErrorCode::MissingInput);
    if (out->dimension != rhi::TextureDimension::Texture2D || out->format != rhi::Format::R16_FLOAT || !(out->usage & rhi::TextureUsage::Storage))
        return fail("output '" + out->debugName + "' must be a 2D R16_FLOAT texture with Storage usage", ErrorCode::WrongFormat);
    if (out->width != width_ || out->height != height_)
        return fail("output '" + out->debugName + "' is " + std::to_string(out->width) + "x" + std::to_string(out->height) + ", the denoiser " + size);
    if (!d.resetHistory && !hasHistory_) return fail("there is no history to reproject yet: the first denoise() after create() must set resetHistory", ErrorCode::InvalidState);
    if (!detail::finite(d.camera.view) || !detail::finite(d.camera.projection) || !detail::finite(d.camera.previousView) || !detail::finite(d.camera.previousProjection) || !detail::finite(d.gbuffer.normalsUnpackScale) ||
        !detail::finite(d.gbuffer.normalsUnpackOffset))
        return fail("the cameras and the normals' unpacking must be finite");
    const glm::mat4 viewProjection = d.camera.projection * d.camera.view, previous = d.camera.previousProjection * d.camera.previousView;
    const glm::mat4 inverse = glm::inverse(viewProjection), inversePrevious = glm::inverse(previous);
    if (!detail::finite(inverse) || std::abs(glm::determinant(viewProjection)) < 1.0e-30f) return fail("the camera's view-projection is not invertible");
    if (!detail::finite(inversePrevious) || std::abs(glm::determinant(previous)) < 1.0e-30f) return fail("the previous camera's view-projection is not invertible");
    if (d.maxHistory < 1 || d.maxHistory > kMaxShadowDenoiseHistory)
        return fail("maxHistory " + std::to_string(d.maxHistory) + " is outside 1.." + std::to_string(kMaxShadowDenoiseHistory));
    if (!(d.clampSigma > 0.0f) || !std::isfinite(d.clampSigma)) return fail("clampSigma must be a finite number > 0");
    if (!(d.depthTolerance > 0.0f) || !std::isfinite(d.depthTolerance)) return fail("depthTolerance must be a finite number > 0");
    if (d.filterPasses > kMaxShadowFilterPasses)
        return fail("filterPasses " + std::to_string(d.filterPasses) + " is outside 0.." + std::to_string(kMaxShadowFilterPasses));

    ShadowDenoiseParams p{};
    p.inverseViewProjection = inverse;
    p.previousViewProjection = previous;
    p.inversePreviousViewProjection = inversePrevious;
    p.eye = glm::vec4(glm::vec3(glm::inverse(d.camera.view)[3]), d.depthTolerance);
    p.normalScale = glm::vec4(d.gbuffer.normalsUnpackScale, d.clampSigma);
    p.normalBias = glm::vec4(d.gbuffer.normalsUnpackOffset, 0.0f);
    p.size = glm::uvec4(width_, height_, classifier.tilesX(), d.camera.reversedDepth ? 1u : 0u);
    p.options = glm::uvec4(d.maxHistory, d.resetHistory ? 1u : 0u, 0u, 0u);
    // Written only when it changes (a still camera: never); the textures ping-pong.
    if (!paramsWritten_ || std::memcmp(&p, lastParams_.data(), sizeof(p)) != 0) {
        device_.writeBuffer(params_, 0, &p, sizeof(p));
        std::memcpy(lastParams_.data(), &p, sizeof(p));
        paramsWritten_ = true;
    }
    const uint32_t cur = current_ ^ 1u, prev = current_;
    bool ok = device_.clearTexture(listed_, 0, 1, rhi::ClearValue{.u = {0u, 0u, 0u, 0u}});

    rhi::DispatchState t;
    t.shader = temporal_;
    t.label = "denoise shadows: temporal";
    t.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
    t.bindings.readBuffers.push(rhi::ReadBufferBinding{1, classifier.tileList(), {}});
    t.bindings.readBuffers.push(rhi::ReadBufferBinding{2, classifier.tileCount(), {}});
    t.bindings.textures.push(rhi::TextureBinding{0, rhi::wholeTexture(d.gbuffer.depth), point_});
    t.bindings.textures.push(rhi::TextureBinding{1, rhi::wholeTexture(d.gbuffer.normals), point_});
    t.bindings.textures.push(rhi::TextureBinding{2, rhi::wholeTexture(history_[prev]), point_});
    t.bindings.textures.push(rhi::TextureBinding{3, rhi::wholeTexture(geometry_[prev]), point_});
    t.bindings.storageImages.push(rhi::storageImage(0, classifier.hitMask(), rhi::Access::Read));
    t.bindings.storageImages.push(rhi::storageImage(1, history_[cur], rhi::Access::Write));
    t.bindings.storageImages.push(rhi::storageImage(2, geometry_[cur], rhi::Access::Write));
    t.bindings.storageImages.push(rhi::storageImage(3, listed_, rhi::Access::Write));
    ok = ok && device_.dispatchIndirect(t, classifier.tileCount(), 0);

    rhi::DispatchState u;
    u.shader = decided_;
    u.label = "denoise shadows: decided tiles";
    u.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
    u.bindings.textures.push(rhi::TextureBinding{0, rhi::wholeTexture(d.gbuffer.depth), point_});
    u.bindings.textures.push(rhi::TextureBinding{1, rhi::wholeTexture(d.gbuffer.normals), point_});
    u.bindings.storageImages.push(rhi::storageImage(0, classifier.hitMask(), rhi::Access::Read));
    u.bindings.storageImages.push(rhi::storageImage(1, history_[cur], rhi::Access::Write));
    u.bindings.storageImages.push(rhi::storageImage(2, geometry_[cur], rhi::Access::Write));
    u.bindings.storageImages.push(rhi::storageImage(3, listed_, rhi::Access::Read));
    u.bindings.storageImages.push(rhi::storageImage(4, d.output, rhi::Access::Write));
    ok = ok && device_.dispatch(u, (width_ + 15) / 16, (height_ + 15) / 16, 1);

    // The à-trous passes: history → filter 0 → filter 1 → … → output; no pass: the history's mean to the output.
    const uint32_t passes = std::max(d.filterPasses, 1u);
    glm::ivec4 steps[kMaxShadowFilterPasses];
    rhi::TextureHandle in = history_[cur];
    for (uint32_t i = 0; i < passes && ok; ++i) {
        const bool last = i + 1 == passes;
        steps[i] = glm::ivec4(d.filterPasses == 0 ? 0 : 1 << i, 0, 0, 0);  // step 0: every tap is the pixel itself
        const rhi::TextureHandle target = last ? d.output : filtered_[i & 1u];
        rhi::DispatchState f;
        f.shader = filter_;
        f.label = "denoise shadows: filter";
        f.bindings.constants.push(rhi::constants(0, steps[i]));
        f.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
        f.bindings.readBuffers.push(rhi::ReadBufferBinding{1, classifier.tileList(), {}});
        f.bindings.readBuffers.push(rhi::ReadBufferBinding{2, classifier.tileCount(), {}});
        f.bindings.textures.push(rhi::TextureBinding{0, rhi::wholeTexture(in), point_});
        f.bindings.textures.push(rhi::TextureBinding{1, rhi::wholeTexture(history_[cur]), point_});
        f.bindings.textures.push(rhi::TextureBinding{2, rhi::wholeTexture(geometry_[cur]), point_});
        f.bindings.storageImages.push(rhi::storageImage(0, classifier.hitMask(), rhi::Access::Read));
        f.bindings.storageImages.push(rhi::storageImage(1, listed_, rhi::Access::Read));
        f.bindings.storageImages.push(rhi::storageImage(2, target, rhi::Access::Write));
        ok = device_.dispatchIndirect(f, classifier.tileCount(), 0);
        in = target;
    }
    if (!ok) return fail("the device refused a pass (see its messages)", ErrorCode::DeviceFailure);
    current_ = cur;
    hasHistory_ = true;
    return true;
}

MemoryUse ShadowDenoiser::memoryUse() const { return detail::MemoryTally(device_).add(params_).add(history_[0]).add(history_[1]).add(geometry_[0]).add(geometry_[1]).add(filtered_[0]).add(filtered_[1]).add(listed_).use(); }

}  // namespace bricklight::shadows
