// vct::ConeTracer: diffuse, specular and ambient light from the clip-map for every pixel of a G-buffer
// (include/bricklight/vct.h; the passes are shaders/vct/trace_diffuse.comp, resolve_diffuse.comp, refine_diffuse.comp
// and trace_specular.comp).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "bricklight/vct.h"
#include "../common/core_shaders.h"
#include "../common/refusal.h"

namespace bricklight::vct {

bool checkConeTraceParams(const ConeTraceParams& p, Error* error) {
    const bricklight::detail::Refusal fail(error, "cone trace parameters");
    auto within = [](float v, float lo, float hi) { return v >= lo && v <= hi; };  // false for NaN
    if (p.diffuseCones < 1 || p.diffuseCones > 32) return fail("diffuseCones " + std::to_string(p.diffuseCones) + " is outside 1..32");
    if (!within(p.diffuseConeAngle, 0.0f, 3.0f)) return fail("diffuseConeAngle " + std::to_string(p.diffuseConeAngle) + " is outside 0..3 radians");
    if (p.tracingSparsity < 1 || p.tracingSparsity > 4) return fail("tracingSparsity " + std::to_string(p.tracingSparsity) + " is outside 1..4");
    if (!within(p.tracingStep, 0.25f, 1.0f)) return fail("tracingStep " + std::to_string(p.tracingStep) + " is outside 0.25..1");
    if (!within(p.specularTracingStep, 0.25f, 1.0f))
        return fail("specularTracingStep " + std::to_string(p.specularTracingStep) + " is outside 0.25..1");
    if (!within(p.opacityCorrection, 0.1f, 10.0f)) return fail("opacityCorrection " + std::to_string(p.opacityCorrection) + " is outside 0.1..10");
    if (p.lightLeakLag > 2) return fail("lightLeakLag " + std::to_string(p.lightLeakLag) + " is outside 0..2");
    if (!within(p.initialOffset, 0.0f, 16.0f)) return fail("initialOffset " + std::to_string(p.initialOffset) + " is outside 0..16 voxels");
    if (!(p.maxDistance >= 0.0f) || !std::isfinite(p.maxDistance)) return fail("maxDistance must be finite and ≥ 0");
    if (!(p.ambientRange >= 0.0f) || !std::isfinite(p.ambientRange)) return fail("ambientRange must be finite and ≥ 0");
    if (!within(p.temporalWeight, 0.0f, 0.98f)) return fail("temporalWeight " + std::to_string(p.temporalWeight) + " is outside 0..0.98");
    if (!within(p.maxSpecularRoughness, 0.0f, 1.0f)) return fail("maxSpecularRoughness is outside 0..1");
    if (!within(p.specularJitter, 0.0f, 1.0f)) return fail("specularJitter " + std::to_string(p.specularJitter) + " is outside 0..1");
    return true;
}

namespace {

// The passes' parameters (TraceParams in shaders/vct/trace_common.glsl, std430).
struct TraceParamsBlock {
    glm::mat4 inverseViewProjection, previousViewProjection, previousInverseViewProjection;
    glm::vec4 eye;
    glm::uvec4 size, lowSize;
    glm::vec4 normalUnpackScale, normalUnpackOffset, cone, limits;
    glm::uvec4 sparseOffset;
    glm::vec4 specular;
};
static_assert(sizeof(TraceParamsBlock) == 336);

rhi::TextureHandle makeTexture(rhi::IDevice& device, uint32_t w, uint32_t h, rhi::Format format, const char* name) {
    rhi::TextureDesc td;
    td.width = w;
    td.height = h;
    td.format = format;
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = name;
    return device.createTexture(td);
}

const uint32_t kNoGuide = 0x7FC00000u;  // NO_PIXEL_GUIDE in trace_common.glsl

void bindWriteImage(rhi::Bindings& bindings, uint8_t slot, rhi::TextureHandle t) {
    bindings.storageImages.push(rhi::storageImage(slot, t, rhi::Access::Write));
}

}  // namespace

std::unique_ptr<ConeTracer> ConeTracer::create(rhi::IDevice& device, const Clipmap& clipmap, const ConeTracerDesc& desc,
                                               Error* error) {
    const uint32_t width = desc.width, height = desc.height;
    const bricklight::detail::Refusal fail(error, "cone tracer");
    if (width == 0 || height == 0 || width > device.capabilities().limits.maxTextureSize2D || height > device.capabilities().limits.maxTextureSize2D)
        return fail("size " + std::to_string(width) + "x" + std::to_string(height) + " is zero or exceeds the device's 2D texture size", ErrorCode::WrongSize);
    // The shaders hold the capacity as a float (exact to 2^24).
    if (desc.refinementEntries != kAutomaticRefinement && desc.refinementEntries > (1u << 24))
        return fail("refinementEntries " + std::to_string(desc.refinementEntries) + " exceeds 16777216");
    shaders::link_bricklight_vct();
    std::unique_ptr<ConeTracer> t(new ConeTracer(device, clipmap));
    t->width_ = width;
    t->height_ = height;
    t->traceDiffuse_ = shaders::createCoreShader(device, "vct/trace_diffuse.comp");
    // A clip-map without emittance (voxel AO) gives only ambient: its resolve and refinement trace occlusion-only cones
    // and keep a one-channel history.
    const bool occlusionOnly = clipmap.desc().emittance == EmittanceMode::None;
    t->resolveDiffuse_ = shaders::createCoreShader(device, occlusionOnly ? "vct/resolve_occlusion.comp" : "vct/resolve_diffuse.comp");
    t->traceSpecular_ = shaders::createCoreShader(device, "vct/trace_specular.comp");
    t->traceDiffuseSdf_ = shaders::createCoreShader(device, "vct/trace_diffuse_sdf.comp");
    t->traceSpecularSdf_ = shaders::createCoreShader(device, "vct/trace_specular_sdf.comp");
    t->traceOcclusion_ = shaders::createCoreShader(device, "vct/trace_occlusion.comp");
    t->refineDiffuse_ = shaders::createCoreShader(device, occlusionOnly ? "vct/refine_occlusion.comp" : "vct/refine_diffuse.comp");
    const char* names[3][2] = {{"vct diffuse history 0", "vct diffuse history 1"},
                               {"vct specular history 0", "vct specular history 1"},
                               {"vct guide 0", "vct guide 1"}};
    for (int i = 0; i < 2; ++i) {
        t->diffuseHistory_[i] = makeTexture(device, width, height, occlusionOnly ? rhi::Format::R16_FLOAT : rhi::Format::RGBA16_FLOAT, names[0][i]);
        if (!occlusionOnly)  // a clip-map without emittance has no specular light to trace (dispatch refuses the output)
            t->specularHistory_[i] = makeTexture(device, width, height, rhi::Format::RGBA16_FLOAT, names[1][i]);
        t->guide_[i] = makeTexture(device, width, height, rhi::Format::RG32_UINT, names[2][i]);
    }
    rhi::BufferDesc bd;
    bd.size = sizeof(TraceParamsBlock);
    bd.usage = rhi::BufferUsage::ShaderRead;
    bd.debugName = "vct trace parameters";
    t->params_ = device.createBuffer(bd);
    // The refinement (shaders/vct/refine_list.glsl): room for a quarter of the pixels' cones — 8 cones of one pixel in
    // 32 (sparse samples fit all but 0.02 % of the atrium's pixels); past it the resolve traces a pixel's cones itself,
    // as before. A listed pixel takes one word; the list holds a word per entry, enough for one-cone tracing.
    t->refineEntries_ = desc.refinementEntries != kAutomaticRefinement ? desc.refinementEntries
                                                                      : std::max<uint32_t>(uint32_t(uint64_t(width) * height / 4), 256u);
    bd.size = std::max<uint64_t>(uint64_t(t->refineEntries_) * 4, 16);
    bd.usage = rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::ShaderRead;
    bd.debugName = "vct refined pixels";
    t->refineList_ = device.createBuffer(bd);
    const uint32_t counts[8] = {0, 1, 1, 0, 0, 0, 0, 0};  // dispatchIndirect's y and z stay 1
    bd.size = sizeof(counts);
    bd.usage = rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::ShaderRead | rhi::BufferUsage::IndirectArgs;
    bd.debugName = "vct refined count A";
    t->refineCounts_[0] = device.createBuffer(bd, counts);
    bd.debugName = "vct refined count B";
    t->refineCounts_[1] = device.createBuffer(bd, counts);
    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = "vct point";
    t->point_ = device.createSampler(sd);
    bool ok = t->traceDiffuse_ && t->resolveDiffuse_ && t->traceSpecular_ && t->traceDiffuseSdf_ && t->traceSpecularSdf_ && t->traceOcclusion_ && t->params_ &&
              t->point_ && t->refineDiffuse_ && t->refineList_ && t->refineCounts_[0] && t->refineCounts_[1];
    for (int i = 0; i < 2; ++i) ok = ok && t->diffuseHistory_[i] && (occlusionOnly || t->specularHistory_[i]) && t->guide_[i];
    if (!ok) return fail("the device could not create the tracing passes or their history", ErrorCode::DeviceFailure);
    rhi::ClearValue none{};
    none.u[0] = kNoGuide;
    for (int i = 0; i < 2; ++i) device.clearTexture(t->guide_[i], 0, 1, none);
    return t;
}

ConeTracer::~ConeTracer() {
    for (rhi::TextureHandle t : {lowDiffuse_, lowGuide_, diffuseHistory_[0], diffuseHistory_[1], specularHistory_[0], specularHistory_[1], guide_[0], guide_[1]})
        if (t) device_.destroy(t);
    for (rhi::ShaderHandle s : {traceDiffuse_, resolveDiffuse_, traceSpecular_, traceDiffuseSdf_, traceSpecularSdf_, traceOcclusion_, refineDiffuse_})
        if (s) device_.destroy(s);
    for (rhi::BufferHandle b : {refineCounts_[0], refineCounts_[1], refineList_})
        if (b) device_.destroy(b);
    for (rhi::ShaderHandle s : {coneSamples_, coneSamplesSdf_, coneSamplesView_})
        if (s) device_.destroy(s);
    if (coneSampleRecord_) device_.destroy(coneSampleRecord_);
    if (params_) device_.destroy(params_);
    if (point_) device_.destroy(point_);
}

bool ConeTracer::bindLowResolution(uint32_t sparsity, Error* error) {
    if (sparsity == sparsity_ && lowDiffuse_) return true;
    for (rhi::TextureHandle t : {lowDiffuse_, lowGuide_})
        if (t) device_.destroy(t);
    const uint32_t w = (width_ + sparsity - 1) / sparsity, h = (height_ + sparsity - 1) / sparsity;
    lowDiffuse_ = makeTexture(device_, w, h, rhi::Format::RGBA16_FLOAT, "vct sparse diffuse");
    lowGuide_ = makeTexture(device_, w, h, rhi::Format::RGBA32_UINT, "vct sparse guide");
    sparsity_ = sparsity;
    if (!lowDiffuse_ || !lowGuide_) {
        if (error) *error = {ErrorCode::DeviceFailure, "cone tracer: the device could not create the sparse tracing targets"};
        sparsity_ = 0;
        return false;
    }
    return true;
}

bool ConeTracer::dispatch(const TraceDesc& d, Error* error) {
    const bricklight::detail::Refusal fail(error, "cone tracer");
    if (!checkConeTraceParams(d.params, error)) return false;
    struct Input {
        const char* name;
        rhi::TextureHandle texture;
        bool required, output;
    };
    const Input inputs[] = {{"depth", d.gbuffer.depth, true, false},           {"normals", d.gbuffer.normals, true, false},
                            {"roughness", d.gbuffer.roughness, true, false},   {"motionVectors", d.gbuffer.motionVectors, false, false},
                            {"outputDiffuse", d.outputDiffuse, true, true}, {"outputSpecular", d.outputSpecular, false, true}};
    for (const Input& in : inputs) {
        if (!in.texture) {
            if (in.required) return fail(std::string(in.name) + " is missing", ErrorCode::MissingInput);
            continue;
        }
        const rhi::TextureDesc* td = device_.describe(in.texture);
        if (!td) return fail(std::string(in.name) + " is not a live texture", ErrorCode::InvalidHandle);
        if (td->width != width_ || td->height != height_)
            return fail(std::string(in.name) + " is " + std::to_string(td->width) + "x" + std::to_string(td->height) + ", not the tracer's " +
                        std::to_string(width_) + "x" + std::to_string(height_));
        if (in.output && (td->format != rhi::Format::RGBA16_FLOAT || !(td->usage & rhi::TextureUsage::Storage)))
            return fail(std::string(in.name) + " must be RGBA16_FLOAT with Storage usage", ErrorCode::WrongFormat);
    }
    if (d.outputSpecular && clipmap_.desc().emittance == EmittanceMode::None)
        return fail("outputSpecular needs a clip-map with emittance: this one has none (voxel AO), so its specular cones would carry no "
                    "light",
                    ErrorCode::Unsupported);
    if (d.gbuffer.roughnessChannel > 3) return fail("roughnessChannel " + std::to_string(d.gbuffer.roughnessChannel) + " is outside 0..3");
    // Motion vectors are read as UV motion (current − previous) as they are.
    if (d.gbuffer.motionVectors && d.gbuffer.motionVectorScale != glm::vec2(1.0f))
        return fail("gbuffer.motionVectorScale must be {1, 1}: the cone tracer reads UV motion as stored", ErrorCode::Unsupported);
    // The cone widths are fitted to perceptual roughness; a G-buffer of GGX α would widen every cone silently.
    if (!d.gbuffer.roughnessPerceptual)
        return fail("gbuffer.roughnessPerceptual = false (GGX α) is not supported: the cone tracer reads perceptual roughness", ErrorCode::Unsupported);
    if (!bindLowResolution(d.params.tracingSparsity, error)) return false;

    const ClipmapDesc& cd = clipmap_.desc();
    const ConeTraceParams& p = d.params;
    const uint32_t s = p.tracingSparsity;
    const uint32_t lowW = (width_ + s - 1) / s, lowH = (height_ + s - 1) / s;
    float angle = p.diffuseConeAngle;
    if (angle == 0.0f) angle = 2.0f * std::min(std::acos(1.0f - 1.0f / float(p.diffuseCones)), 1.4f);  // 2π / cones sr each
    // The pixel of each block traced this frame: every one of the s² in turn, in a scattered order.
    const uint32_t phase = (frame_ * 3u) % (s * s);
    TraceParamsBlock b{};
    b.inverseViewProjection = glm::inverse(d.camera.projection * d.camera.view);
    b.previousViewProjection = d.camera.previousProjection * d.camera.previousView;
    b.previousInverseViewProjection = glm::inverse(b.previousViewProjection);
    b.eye = glm::vec4(d.cameraPosition, 0.0f);
    b.size = glm::uvec4(width_, height_, s, frame_);
    b.lowSize = glm::uvec4(lowW, lowH, p.diffuseCones, (d.resetHistory || frame_ == 0 ? 1u : 0u) | (d.gbuffer.motionVectors ? 2u : 0u));
    b.normalUnpackScale = glm::vec4(d.gbuffer.normalsUnpackScale, float(d.gbuffer.roughnessChannel));
    b.normalUnpackOffset = glm::vec4(d.gbuffer.normalsUnpackOffset, p.maxSpecularRoughness);
    b.cone = glm::vec4(2.0f * std::tan(0.5f * angle), p.tracingStep, p.opacityCorrection, p.initialOffset);
    b.limits = glm::vec4(p.maxDistance, p.ambientRange > 0.0f ? p.ambientRange : 8.0f * cd.finestVoxelSize, p.temporalWeight, float(p.lightLeakLag));
    // The diffuse cones turn by the golden angle's fraction of a turn each frame (a low-discrepancy sequence).
    const float rotation = std::fmod(float(frame_) * 0.61803399f, 1.0f) * 6.2831853f;
    uint32_t stepBits, rotationBits;
    std::memcpy(&stepBits, &p.specularTracingStep, 4);
    std::memcpy(&rotationBits, &rotation, 4);
    b.sparseOffset = glm::uvec4(phase % s, phase / s, stepBits, rotationBits);
    b.specular = glm::vec4(p.specularJitter, float(frame_ % 4096u), float(refineEntries_), 0.0f);
    device_.writeBuffer(params_, 0, &b, sizeof(b));

    const uint32_t cur = frame_ & 1u, prev = cur ^ 1u;
    auto common = [&](rhi::Bindings& bindings) { bindCommon(bindings, d); };
    device_.beginMarker("vct diffuse");
    rhi::DispatchState trace;
    trace.shader = d.occlusionField ? traceDiffuseSdf_ : (cd.emittance == EmittanceMode::None ? traceOcclusion_ : traceDiffuse_);
    trace.label = "vct trace diffuse";
    common(trace.bindings);
    bindField(trace.bindings, d);
    bindWriteImage(trace.bindings, 0, lowDiffuse_);
    bindWriteImage(trace.bindings, 1, lowGuide_);
    device_.dispatch(trace, (lowW + 7) / 8, (lowH + 7) / 8, 1);

    rhi::DispatchState resolve;
    resolve.shader = resolveDiffuse_;
    resolve.label = "vct resolve diffuse";
    common(resolve.bindings);
    resolve.bindings.textures.push(rhi::TextureBinding{4, rhi::wholeTexture(lowDiffuse_), point_});
    resolve.bindings.textures.push(rhi::TextureBinding{5, rhi::wholeTexture(lowGuide_), point_});
    resolve.bindings.textures.push(rhi::TextureBinding{6, rhi::wholeTexture(diffuseHistory_[prev]), point_});
    resolve.bindings.textures.push(rhi::TextureBinding{7, rhi::wholeTexture(guide_[prev]), point_});
    bindWriteImage(resolve.bindings, 0, d.outputDiffuse);
    bindWriteImage(resolve.bindings, 1, diffuseHistory_[cur]);
    bindWriteImage(resolve.bindings, 2, guide_[cur]);
    // The counts this frame's resolve adds to were zeroed by the previous frame's (both were created holding zeros and
    // the dispatch arguments' 1s), which zeroes the other for the next.
    resolve.bindings.storageBuffers.push(rhi::StorageBufferBinding{0, refineCounts_[cur], {}, rhi::Access::Atomic});
    resolve.bindings.storageBuffers.push(rhi::StorageBufferBinding{1, refineList_, {}, rhi::Access::Write});
    resolve.bindings.storageBuffers.push(rhi::StorageBufferBinding{2, refineCounts_[prev], {}, rhi::Access::Write});
    device_.dispatch(resolve, (width_ + 7) / 8, (height_ + 7) / 8, 1);
    dispatchRefinement(d);
    device_.endMarker();

    if (d.outputSpecular) {
        device_.beginMarker("vct specular");
        rhi::DispatchState spec;
        spec.shader = d.occlusionField ? traceSpecularSdf_ : traceSpecular_;
        spec.label = "vct trace specular";
        common(spec.bindings);
        bindField(spec.bindings, d);
        spec.bindings.textures.push(rhi::TextureBinding{6, rhi::wholeTexture(specularHistory_[prev]), point_});
        spec.bindings.textures.push(rhi::TextureBinding{7, rhi::wholeTexture(guide_[prev]), point_});
        bindWriteImage(spec.bindings, 0, d.outputSpecular);
        bindWriteImage(spec.bindings, 1, specularHistory_[cur]);
        device_.dispatch(spec, (width_ + 7) / 8, (height_ + 7) / 8, 1);
        device_.endMarker();
    }
    ++frame_;
    latest_ = d;
    return true;
}

// The refined pixels' cones, one to an invocation, each pixel's sum and blend (shaders/vct/refine_list.glsl).
void ConeTracer::dispatchRefinement(const TraceDesc& d) {
    const uint32_t cur = frame_ & 1u, prev = cur ^ 1u;
    rhi::DispatchState refine;
    refine.shader = refineDiffuse_;
    refine.label = "vct refine diffuse";
    bindCommon(refine.bindings, d);
    refine.bindings.readBuffers.push(rhi::ReadBufferBinding{4, refineCounts_[cur], {}});
    refine.bindings.readBuffers.push(rhi::ReadBufferBinding{5, refineList_, {}});
    refine.bindings.textures.push(rhi::TextureBinding{6, rhi::wholeTexture(diffuseHistory_[prev]), point_});
    refine.bindings.textures.push(rhi::TextureBinding{7, rhi::wholeTexture(guide_[prev]), point_});
    bindWriteImage(refine.bindings, 0, d.outputDiffuse);
    bindWriteImage(refine.bindings, 1, diffuseHistory_[cur]);
    device_.dispatchIndirect(refine, refineCounts_[cur], 0);
}

uint32_t ConeTracer::readRefinedPixels() {
    if (frame_ == 0) return 0;
    uint32_t counts[8] = {};
    device_.readBuffer(refineCounts_[(frame_ - 1u) & 1u], 0, sizeof(counts), counts);
    return counts[6];  // REFINE_LISTED in shaders/vct/refine_list.glsl
}

void ConeTracer::bindField(rhi::Bindings& bindings, const TraceDesc& d) const {
    // The field's atlas after the clip-map's textures (8..14), its buffers before the parameters (6) and frame (7).
    if (d.occlusionField) d.occlusionField->traceBindings(bindings, sdf::TraceSlots{15, 0});
}

void ConeTracer::bindCommon(rhi::Bindings& bindings, const TraceDesc& d) const {
    uint8_t slot = 0;
    for (rhi::TextureHandle t : {d.gbuffer.depth, d.gbuffer.normals, d.gbuffer.roughness, d.gbuffer.motionVectors ? d.gbuffer.motionVectors : d.gbuffer.depth})
        bindings.textures.push(rhi::TextureBinding{slot++, rhi::wholeTexture(t), point_});
    clipmap_.traceBindings(bindings, 8, 7);
    bindings.readBuffers.push(rhi::ReadBufferBinding{6, params_, {}});
}

MemoryUse ConeTracer::memoryUse() const {
    MemoryUse use;
    for (rhi::TextureHandle t : {lowDiffuse_, lowGuide_, diffuseHistory_[0], diffuseHistory_[1], specularHistory_[0], specularHistory_[1], guide_[0], guide_[1]})
        if (const rhi::TextureDesc* d = device_.describe(t)) {
            use.resources.push_back({d->debugName, rhi::subresourceBytes(*d, {})});
            use.totalBytes += use.resources.back().bytes;
        }
    for (rhi::BufferHandle b : {params_, refineCounts_[0], refineCounts_[1], refineList_})
        if (const rhi::BufferDesc* d = device_.describe(b)) {
            use.resources.push_back({d->debugName, d->size});
            use.totalBytes += d->size;
        }
    return use;
}

}  // namespace bricklight::vct
