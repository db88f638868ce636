// The shadow classifier (include/bricklight/shadows/classifier.h): checks, resources and the classification pass
// (shaders/shadows/classify_shadows.comp). docs/shadows.md.
#include <cmath>
#include <cstring>

#include "bricklight/shadows/classifier.h"
#include "../common/memory_tally.h"
#include "../common/technique_setup.h"
#include "../common/refusal.h"

namespace bricklight::shadows {

namespace {

constexpr uint32_t kCountWords = 8;
constexpr uint32_t kAlphaCacheHeaderWords = 4;  // BL_ALPHA_CACHE_HEADER: the least an alpha cache buffer holds

// The pass's parameters (the Params block of classify_shadows.comp, std430).
struct ShadowClassifyParams {
    glm::mat4 inverseViewProjection;
    glm::mat4 worldToShadow[kMaxShadowCascades];
    glm::vec4 uvRect[kMaxShadowCascades];
    glm::vec4 sun, depthRange, normalScale, normalBias;
    glm::uvec4 size, options, options2;
    glm::vec4 trace, trust;
};
static_assert(sizeof(ShadowClassifyParams) == 64 * 5 + 16 * 4 + 16 * 4 + 16 * 3 + 16 * 2);
static_assert(sizeof(ShadowClassifyParams) == kShadowParamsBytes);

}  // namespace

std::unique_ptr<ShadowClassifier> ShadowClassifier::create(rhi::IDevice& device, const ShadowClassifierDesc& desc, Error* error) {
    const uint32_t width = desc.width, height = desc.height;
    const bricklight::detail::Refusal fail(error, "shadow classifier");
    if (const std::string problem = detail::sizeProblem(width, height); !problem.empty()) return fail(problem);
    std::unique_ptr<ShadowClassifier> c(new ShadowClassifier(device));
    c->width_ = width;
    c->height_ = height;
    detail::createShaders(device, shaders::link_bricklight_shadows, {std::pair{"shadows/classify_shadows.comp", &c->classify_}, std::pair{"shadows/trace_shadows.comp", &c->trace_},
                                std::pair{"shadows/resolve_shadows.comp", &c->resolve_}});
    const uint64_t tiles = uint64_t(c->tilesX()) * c->tilesY();
    rhi::BufferDesc bd;
    bd.size = tiles * 16;
    bd.usage = rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::ShaderRead;
    bd.debugName = "shadow tile list";
    c->tiles_ = device.createBuffer(bd);
    const uint32_t counts[kCountWords] = {0, 1, 1, 0, 0, 0, 0, 0};  // dispatchIndirect's y and z stay 1
    bd.size = kCountWords * 4;
    bd.usage = rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::ShaderRead | rhi::BufferUsage::IndirectArgs;
    bd.debugName = "shadow tile count A";
    c->counts_[0] = device.createBuffer(bd, counts);
    bd.debugName = "shadow tile count B";
    c->counts_[1] = device.createBuffer(bd, counts);
    bd.size = sizeof(ShadowClassifyParams);
    bd.usage = rhi::BufferUsage::ShaderRead;
    bd.debugName = "shadow classifier parameters";
    c->params_ = device.createBuffer(bd);
    rhi::TextureDesc td;
    td.format = rhi::Format::R32_UINT;
    td.width = c->tilesX();
    td.height = c->tilesY();
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = "shadow hit mask";
    c->hitMask_ = device.createTexture(td);
    td.debugName = "shadow sure mask";
    c->sureMask_ = device.createTexture(td);
    rhi::SamplerDesc sampler;
    sampler.minFilter = sampler.magFilter = sampler.mipFilter = rhi::Filter::Nearest;
    sampler.debugName = "shadow classifier point";
    c->point_ = device.createSampler(sampler);
    const uint32_t noAlphaCache[kAlphaCacheHeaderWords] = {};  // word 0 = 0: no cache kept (bricklight/alpha_cache.glsl)
    bd.size = sizeof(noAlphaCache);
    bd.usage = rhi::BufferUsage::ShaderRead | rhi::BufferUsage::ShaderWrite;
    bd.debugName = "shadow classifier: no alpha cache";
    c->alphaCacheNone_ = device.createBuffer(bd, noAlphaCache);
    if (!c->classify_ || !c->trace_ || !c->resolve_ || !c->tiles_ || !c->counts_[0] || !c->counts_[1] || !c->params_ || !c->hitMask_ || !c->sureMask_ || !c->point_ ||
        !c->alphaCacheNone_)
        return fail("the device could not create the classifier's buffers, hit mask or pass (see its messages)", ErrorCode::DeviceFailure);
    return c;
}

ShadowClassifier::~ShadowClassifier() {
    for (rhi::BufferHandle b : {tiles_, counts_[0], counts_[1], params_, alphaCacheNone_})
        if (b) device_.destroy(b);
    for (rhi::TextureHandle t : {hitMask_, sureMask_})
        if (t) device_.destroy(t);
    if (point_) device_.destroy(point_);
    for (rhi::ShaderHandle s : {classify_, trace_, resolve_})
        if (s) device_.destroy(s);
}

bool ShadowClassifier::classify(const ShadowClassifyDesc& d, Error* error) {
    const bricklight::detail::Refusal fail(error, "shadow classifier");
    auto sized = [&](rhi::TextureHandle t, const char* name, bool depth) -> bool {
        const rhi::TextureDesc* td = t ? device_.describe(t) : nullptr;
        if (!td) return fail(std::string(name) + " is missing or not a live texture", ErrorCode::MissingInput);
        if (td->dimension != rhi::TextureDimension::Texture2D || !(td->usage & rhi::TextureUsage::Sampled))
            return fail(std::string(name) + " '" + td->debugName + "' must be a sampled 2D texture", ErrorCode::WrongFormat);
        if (depth && td->format != rhi::Format::D32_FLOAT && td->format != rhi::Format::R32_FLOAT)
            return fail(std::string(name) + " '" + td->debugName + "' must be D32_FLOAT or R32_FLOAT");
        return true;
    };
    if (d.mode != ShadowClassifyMode::Normals && d.mode != ShadowClassifyMode::Cascades)
        return fail("mode " + std::to_string(uint32_t(d.mode)) + " is not Normals or Cascades");
    if (!sized(d.gbuffer.depth, "depth", true) || !sized(d.gbuffer.normals, "normals", false)) return false;
    for (rhi::TextureHandle t : {d.gbuffer.depth, d.gbuffer.normals}) {
        const rhi::TextureDesc* td = device_.describe(t);
        if (td->width != width_ || td->height != height_)
            return fail("'" + td->debugName + "' is " + std::to_string(td->width) + "x" + std::to_string(td->height) + ", the classifier " +
                        std::to_string(width_) + "x" + std::to_string(height_));
    }
    if (!detail::finite(d.camera.view) || !detail::finite(d.camera.projection) || !detail::finite(d.gbuffer.normalsUnpackScale) || !detail::finite(d.gbuffer.normalsUnpackOffset))
        return fail("the camera matrices and the normals' unpacking must be finite");
    const glm::mat4 viewProjection = d.camera.projection * d.camera.view;
    const glm::mat4 inverse = glm::inverse(viewProjection);
    if (!detail::finite(inverse) || std::abs(glm::determinant(viewProjection)) < 1.0e-30f) return fail("the camera's view-projection is not invertible");
    const float sunLength = detail::finite(d.sunDirection) ? glm::length(d.sunDirection) : 0.0f;
    if (!(sunLength > 1.0e-6f) || !std::isfinite(sunLength)) return fail("sunDirection must be a finite, non-zero vector");
    if (!(d.sunAngle >= 0.0f && d.sunAngle < 0.5f)) return fail("sunAngle " + std::to_string(d.sunAngle) + " is outside 0..0.5 radians");
    if (!(d.rayPushOff >= 0.0f) || !std::isfinite(d.rayPushOff)) return fail("rayPushOff must be a finite number ≥ 0");
    if (!(d.rayNormalOffset >= 0.0f) || !std::isfinite(d.rayNormalOffset)) return fail("rayNormalOffset must be a finite number ≥ 0");
    // The field saturates at 2 brixels (kDistanceBandBrixels), 3.33 hit epsilons: a larger sure-miss epsilon would
    // take every voxel with a brick for a hit.
    if (!(d.sureHitEpsilon > 0.0f && d.sureHitEpsilon <= d.sureMissEpsilon && d.sureMissEpsilon <= 3.0f))
        return fail("sureHitEpsilon and sureMissEpsilon must satisfy 0 < sureHitEpsilon <= sureMissEpsilon <= 3");
    if (!(d.selfClearance >= 0.0f && d.selfClearance <= 16.0f)) return fail("selfClearance must lie in 0..16 brixels");
    if (d.tileCutOff > 32) return fail("tileCutOff " + std::to_string(d.tileCutOff) + " is more than a tile's 32 pixels");
    if (d.alphaCache) {
        // trace_shadows.comp reads it as a storage buffer (bricklight/alpha_cache.glsl): its header, then the cells.
        const rhi::BufferDesc* ad = device_.describe(d.alphaCache);
        if (!ad) return fail("alphaCache is not a live buffer (gi::GiContext::alphaCacheBuffer() of a living context)", ErrorCode::InvalidHandle);
        if (!(ad->usage & rhi::BufferUsage::ShaderWrite))
            return fail("alphaCache '" + ad->debugName + "' was not created with BufferUsage::ShaderWrite (it is bound as a storage buffer)", ErrorCode::WrongFormat);
        if (ad->size < kAlphaCacheHeaderWords * 4)
            return fail("alphaCache '" + ad->debugName + "' holds " + std::to_string(ad->size) + " bytes, less than the cache's 16-byte header");
    }
    ShadowClassifyParams p{};
    p.inverseViewProjection = inverse;
    p.sun = glm::vec4(d.sunDirection / sunLength, std::tan(0.5f * d.sunAngle));
    p.normalScale = glm::vec4(d.gbuffer.normalsUnpackScale, d.blockerOffset);
    p.normalBias = glm::vec4(d.gbuffer.normalsUnpackOffset, d.rayPushOff);
    p.size = glm::uvec4(width_, height_, tilesX(), uint32_t(d.mode));
    p.options = glm::uvec4(0u, d.blockerTaps, d.rejectLitPixels ? 1u : 0u, d.cascadeRayInterval ? 1u : 0u);
    p.options2 = glm::uvec4(d.tileCutOff, d.camera.reversedDepth ? 1u : 0u, 1u, 1u);
    p.size.w |= d.markUnsurePixels ? 2u : 0u;  // bit 1: resolve() marks unsure pixels
    // y: the field's hit epsilon scale; z: the radius of the disc the soft rays' directions cover (tan of half the
    // sun's angle, 0 for hard rays); w: the frame's sample index, as a float (exact below 2^24; a float, not its bits,
    // so that no denormal flush can touch it).
    p.trace = glm::vec4(d.rayNormalOffset, 1.0f, d.softShadows ? std::tan(0.5f * d.sunAngle) : 0.0f, float(d.frameIndex & 0xFFFFFFu));
    p.trust = glm::vec4(d.sureHitEpsilon, d.sureMissEpsilon, d.selfClearance, d.sureRaysOnly ? 1.0f : 0.0f);
    rhi::TextureHandle shadowMap = d.gbuffer.depth;  // bound in Normals mode too (never read there)
    if (d.mode == ShadowClassifyMode::Cascades) {
        if (!sized(d.shadowMap, "shadowMap", true)) return false;
        if (d.cascadeCount < 1 || d.cascadeCount > kMaxShadowCascades)
            return fail("cascadeCount " + std::to_string(d.cascadeCount) + " is outside 1.." + std::to_string(kMaxShadowCascades));
        if (d.blockerTaps != 8 && d.blockerTaps != 16 && d.blockerTaps != 24 && d.blockerTaps != 32)
            return fail("blockerTaps " + std::to_string(d.blockerTaps) + " is not 8, 16, 24 or 32");
        if (!(d.blockerOffset >= 0.0f && d.blockerOffset < 1.0f)) return fail("blockerOffset must lie in 0..1 (shadow-map depth)");
        for (uint32_t c = 0; c < d.cascadeCount; ++c) {
            const ShadowCascade& s = d.cascades[c];
            const glm::vec4 r = s.uvRect;
            if (!detail::finite(s.worldToShadow) || !(s.depthRange > 0.0f) || !std::isfinite(s.depthRange))
                return fail("cascade " + std::to_string(c) + ": worldToShadow must be finite and depthRange positive");
            if (!(r.x >= 0.0f && r.y >= 0.0f && r.z <= 1.0f && r.w <= 1.0f && r.x < r.z && r.y < r.w))
                return fail("cascade " + std::to_string(c) + ": uvRect must be a non-empty part of [0, 1]²");
            p.worldToShadow[c] = s.worldToShadow;
            p.uvRect[c] = r;
            p.depthRange[int(c)] = s.depthRange;
        }
        const rhi::TextureDesc* sm = device_.describe(d.shadowMap);
        p.options.x = d.cascadeCount;
        p.options2.z = sm->width;
        p.options2.w = sm->height;
        shadowMap = d.shadowMap;
    }
    // The parameters only when they changed (a still camera and sun: never).
    if (!paramsWritten_ || std::memcmp(&p, lastParams_.data(), sizeof(p)) != 0) {
        device_.writeBuffer(params_, 0, &p, sizeof(p));
        std::memcpy(lastParams_.data(), &p, sizeof(p));
        paramsWritten_ = true;
    }
    // The counts this classification adds to were zeroed by the previous one (both were created holding zeros and the
    // dispatch arguments' y and z, 1, 1), which this one's first thread zeroes for the next: no clear and barrier ahead
    // of the pass.
    const uint32_t counting = countIndex_ ^ 1u;
    rhi::DispatchState s;
    s.shader = classify_;
    s.label = "classify shadows";
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
    s.bindings.textures.push(rhi::TextureBinding{0, rhi::wholeTexture(d.gbuffer.depth), point_});
    s.bindings.textures.push(rhi::TextureBinding{1, rhi::wholeTexture(d.gbuffer.normals), point_});
    s.bindings.textures.push(rhi::TextureBinding{2, rhi::wholeTexture(shadowMap), point_});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{0, tiles_, {}, rhi::Access::Write});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{1, counts_[counting], {}, rhi::Access::Atomic});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{2, counts_[countIndex_], {}, rhi::Access::Write});
    s.bindings.storageImages.push(rhi::storageImage(0, hitMask_, rhi::Access::Write));
    s.bindings.storageImages.push(rhi::storageImage(1, sureMask_, rhi::Access::Write));
    if (!device_.dispatch(s, (tilesX() + 3) / 4, (tilesY() + 3) / 4, 1)) return fail("the device refused the classification (see its messages)", ErrorCode::DeviceFailure);  // 4 × 4 tiles a group
    countIndex_ = counting;
    depth_ = d.gbuffer.depth;
    normals_ = d.gbuffer.normals;
    alphaCache_ = d.alphaCache;
    classified_ = true;
    return true;
}

bool ShadowClassifier::trace(const sdf::SdfScene& field, Error* error) {
    if (!classified_ || !device_.describe(depth_) || !device_.describe(normals_)) {
        if (error) *error = {ErrorCode::InvalidState, "shadow classifier: trace() needs a classify() whose depth and normals are still live"};
        return false;
    }
    if (alphaCache_ && !device_.describe(alphaCache_)) {
        if (error) *error = {ErrorCode::InvalidState, "shadow classifier: trace() needs the classify()'s alphaCache still live"};
        return false;
    }
    rhi::DispatchState s;
    s.shader = trace_;
    s.label = "trace shadow rays";
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{1, tiles_, {}});
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{2, tileCount(), {}});
    s.bindings.textures.push(rhi::TextureBinding{0, rhi::wholeTexture(depth_), point_});
    s.bindings.textures.push(rhi::TextureBinding{1, rhi::wholeTexture(normals_), point_});
    s.bindings.storageImages.push(rhi::storageImage(0, hitMask_, rhi::Access::ReadWrite));
    s.bindings.storageImages.push(rhi::storageImage(1, sureMask_, rhi::Access::ReadWrite));
    // Atomic: a ray that reaches its bound on cards passed is counted in the cache's header (gi::GiContext::raysAtAlphaBound).
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{7, alphaCache_ ? alphaCache_ : alphaCacheNone_, {}, rhi::Access::Atomic});
    field.traceBindings(s.bindings);
    if (!device_.dispatchIndirect(s, tileCount(), 0)) {
        if (error) *error = {ErrorCode::DeviceFailure, "shadow classifier: the device refused the trace (see its messages)"};
        return false;
    }
    return true;
}

bool ShadowClassifier::resolve(rhi::TextureHandle output, Error* error) {
    const rhi::TextureDesc* d = output ? device_.describe(output) : nullptr;
    if (!d || d->format != rhi::Format::R16_FLOAT || !(d->usage & rhi::TextureUsage::Storage) || d->width != width_ || d->height != height_ ||
        d->dimension != rhi::TextureDimension::Texture2D) {
        if (error)
            *error = {ErrorCode::WrongFormat, "shadow classifier: the shadow mask must be a live 2D R16_FLOAT texture with Storage usage of " + std::to_string(width_) + "x" +
                     std::to_string(height_)};
        return false;
    }
    if (!classified_) {
        if (error) *error = {ErrorCode::InvalidState, "shadow classifier: resolve() needs a classify() first"};
        return false;
    }
    rhi::DispatchState s;
    s.shader = resolve_;
    s.label = "resolve shadow mask";
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
    s.bindings.storageImages.push(rhi::storageImage(0, hitMask_, rhi::Access::Read));
    s.bindings.storageImages.push(rhi::storageImage(1, output, rhi::Access::Write));
    s.bindings.storageImages.push(rhi::storageImage(2, sureMask_, rhi::Access::Read));
    return device_.dispatch(s, (width_ + 15) / 16, (height_ + 15) / 16, 1);
}

ShadowClassifyCounts ShadowClassifier::readCounts() {
    uint32_t w[kCountWords] = {};
    ShadowClassifyCounts c;
    if (!device_.readBuffer(tileCount(), 0, sizeof(w), w)) return c;
    c.listedTiles = w[7];
    c.cutOffTiles = w[3];
    c.rayPixels = w[4];
    c.cutOffPixels = w[5];
    c.activePixels = w[6];
    return c;
}

MemoryUse ShadowClassifier::memoryUse() const { return detail::MemoryTally(device_).add(tiles_).add(counts_[0]).add(counts_[1]).add(params_).add(alphaCacheNone_).add(hitMask_).add(sureMask_).use(); }

}  // namespace bricklight::shadows
