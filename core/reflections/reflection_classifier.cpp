// The reflection classifier (include/bricklight/reflections/classifier.h): checks, resources, the classification
// (shaders/reflections/classify_reflections.comp) and the arguments pass (reflection_args.comp). The screen-space
// trace and the debug view are in reflection_trace.cpp. docs/reflections.md.
#include <cmath>
#include <cstring>
#include <vector>

#include "bricklight/reflections/classifier.h"
#include "reflection_params.h"
#include "../common/memory_tally.h"
#include "../common/technique_setup.h"
#include "../common/refusal.h"

namespace bricklight::reflections {

namespace {

bool invertible(const glm::mat4& m) {
    return detail::finite(m) && std::abs(glm::determinant(m)) > 1.0e-30f && detail::finite(glm::inverse(m));
}

}  // namespace

std::unique_ptr<ReflectionClassifier> ReflectionClassifier::create(rhi::IDevice& device, const ReflectionClassifierDesc& desc, Error* error) {
    const uint32_t width = desc.width, height = desc.height;
    const bricklight::detail::Refusal fail(error, "reflection classifier");
    if (const std::string problem = detail::sizeProblem(width, height); !problem.empty()) return fail(problem);
    std::unique_ptr<ReflectionClassifier> c(new ReflectionClassifier(device));
    c->width_ = width;
    c->height_ = height;
    detail::createShaders(device, shaders::link_bricklight_reflections, {std::pair{"reflections/classify_reflections.comp", &c->classify_}, std::pair{"reflections/reflection_args.comp", &c->args_},
                                std::pair{"reflections/trace_reflections_screen.comp", &c->trace_}, std::pair{"reflections/reflection_debug.comp", &c->debug_},
                                std::pair{"reflections/clear_rgba16f.comp", &c->clear_}});
    const uint64_t tiles = uint64_t(c->tilesX()) * c->tilesY();
    auto buffer = [&](uint64_t bytes, uint32_t usage, const char* name) {
        rhi::BufferDesc bd;
        bd.size = bytes;
        bd.usage = usage;
        bd.debugName = name;
        return device.createBuffer(bd);
    };
    const uint32_t readWrite = rhi::BufferUsage::ShaderWrite | rhi::BufferUsage::ShaderRead;
    c->screenList_ = buffer(tiles * 64 * 4, readWrite, "reflection screen-space ray list");
    c->sdfList_ = buffer(uint64_t(width) * height * 4, readWrite, "reflection SDF ray list");
    c->denoiseList_ = buffer(tiles * 4, readWrite, "reflection denoiser tile list");
    {
        const uint32_t zeros[kReflectionCountWords] = {};
        rhi::BufferDesc bd;
        bd.size = sizeof(zeros);
        bd.usage = readWrite | rhi::BufferUsage::IndirectArgs;
        bd.debugName = "reflection ray counts A";
        c->counts_[0] = device.createBuffer(bd, zeros);
        bd.debugName = "reflection ray counts B";
        c->counts_[1] = device.createBuffer(bd, zeros);
    }
    c->params_ = buffer(sizeof(ReflectionParams), rhi::BufferUsage::ShaderRead, "reflection classifier parameters");
    rhi::TextureDesc td;
    td.format = rhi::Format::R32_UINT;
    td.width = c->tilesX();
    td.height = c->tilesY();
    td.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td.debugName = "reflection hit counter A";
    c->hitCounters_[0] = device.createTexture(td);
    td.debugName = "reflection hit counter B";
    c->hitCounters_[1] = device.createTexture(td);
    td.debugName = "reflection tile info";
    c->tileInfo_ = device.createTexture(td);
    td.debugName = "reflection tile statistics";
    c->tileStats_ = device.createTexture(td);
    const float still[2] = {0.0f, 0.0f};
    td.format = rhi::Format::RG32_FLOAT;
    td.width = td.height = 1;
    td.usage = rhi::TextureUsage::Sampled;
    td.debugName = "reflection no motion";
    c->noMotion_ = device.createTexture(td, still);
    rhi::SamplerDesc sampler;
    sampler.minFilter = sampler.magFilter = sampler.mipFilter = rhi::Filter::Nearest;
    sampler.debugName = "reflection classifier point";
    c->point_ = device.createSampler(sampler);
    sampler.minFilter = sampler.magFilter = rhi::Filter::Linear;
    sampler.debugName = "reflection classifier linear";
    c->linear_ = device.createSampler(sampler);
    if (!c->classify_ || !c->args_ || !c->trace_ || !c->debug_ || !c->clear_ || !c->screenList_ || !c->sdfList_ || !c->denoiseList_ || !c->counts_[0] || !c->counts_[1] || !c->params_ ||
        !c->hitCounters_[0] || !c->hitCounters_[1] || !c->tileInfo_ || !c->tileStats_ || !c->noMotion_ || !c->point_ || !c->linear_)
        return fail("the device could not create the classifier's buffers, textures or passes (see its messages)", ErrorCode::DeviceFailure);
    rhi::ClearValue zero{};
    for (rhi::TextureHandle t : {c->hitCounters_[0], c->hitCounters_[1], c->tileInfo_, c->tileStats_}) device.clearTexture(t, 0, 1, zero);
    return c;
}

ReflectionClassifier::~ReflectionClassifier() {
    for (rhi::BufferHandle b : {screenList_, sdfList_, denoiseList_, counts_[0], counts_[1], params_})
        if (b) device_.destroy(b);
    for (rhi::TextureHandle t : {hitCounters_[0], hitCounters_[1], tileInfo_, tileStats_, noMotion_})
        if (t) device_.destroy(t);
    for (rhi::SamplerHandle s : {point_, linear_})
        if (s) device_.destroy(s);
    for (rhi::ShaderHandle s : {classify_, args_, trace_, debug_, clear_})
        if (s) device_.destroy(s);
}

bool ReflectionClassifier::writeParams(const void* bytes, size_t offset, size_t size) {
    // Only when changed: a still camera and the same settings write nothing but the frame index.
    if (paramsWritten_ && std::memcmp(lastParams_.data() + offset, bytes, size) == 0) return true;
    std::memcpy(lastParams_.data() + offset, bytes, size);
    if (!paramsWritten_) {  // the first write fills every section, so that no pass reads undefined bytes
        paramsWritten_ = true;
        return device_.writeBuffer(params_, 0, lastParams_.data(), sizeof(ReflectionParams));
    }
    return device_.writeBuffer(params_, offset, bytes, size);
}

bool ReflectionClassifier::classify(const ReflectionClassifyDesc& d, Error* error) {
    const bricklight::detail::Refusal fail(error, "reflection classifier");
    using Kind = rhi::FormatInfo::Kind;
    // A live, sampled 2D texture of the classifier's size with a readable kind and enough channels.
    auto check = [&](rhi::TextureHandle t, const char* name, uint32_t channels, bool depth, bool signedFloat) -> bool {
        const rhi::TextureDesc* td = t ? device_.describe(t) : nullptr;
        if (!td) return fail(std::string(name) + " is missing or not a live texture", ErrorCode::MissingInput);
        const std::string named = std::string(name) + " '" + td->debugName + "'";
        if (td->dimension != rhi::TextureDimension::Texture2D || !(td->usage & rhi::TextureUsage::Sampled))
            return fail(named + " must be a sampled 2D texture", ErrorCode::WrongFormat);
        if (td->width != width_ || td->height != height_)
            return fail(named + " is " + std::to_string(td->width) + "x" + std::to_string(td->height) + ", the classifier " + std::to_string(width_) +
                        "x" + std::to_string(height_));
        const rhi::FormatInfo& f = rhi::formatInfo(td->format);
        if (depth && td->format != rhi::Format::D32_FLOAT && td->format != rhi::Format::R32_FLOAT)
            return fail(named + " must be D32_FLOAT or R32_FLOAT, not " + f.name);
        if (!depth && (f.channels < channels || td->format == rhi::Format::D32_FLOAT ||
                       (signedFloat ? f.kind != Kind::Float : (f.kind != Kind::Float && f.kind != Kind::Unorm && f.kind != Kind::Srgb && f.kind != Kind::PackedFloat))))
            return fail(named + " has format " + f.name + ": it needs " + std::to_string(channels) + (signedFloat ? " float" : " float or unorm") +
                        " channel(s)", ErrorCode::WrongFormat);
        return true;
    };
    if (!check(d.gbuffer.depth, "depth", 1, true, false) || !check(d.gbuffer.normals, "normals", 3, false, false)) return false;
    if (d.gbuffer.roughnessChannel > 3) return fail("roughnessChannel " + std::to_string(d.gbuffer.roughnessChannel) + " is outside 0..3");
    if (!check(d.gbuffer.roughness, "roughness", d.gbuffer.roughnessChannel + 1, false, false)) return false;
    if (d.gbuffer.motionVectors && !check(d.gbuffer.motionVectors, "motionVectors", 2, false, true)) return false;
    if (!detail::finite(d.camera.view) || !detail::finite(d.camera.projection) || !detail::finite(d.camera.previousView) || !detail::finite(d.camera.previousProjection))
        return fail("the camera matrices (view, projection, previousView, previousProjection) must be finite");
    const glm::mat4 viewProjection = d.camera.projection * d.camera.view, previousViewProjection = d.camera.previousProjection * d.camera.previousView;
    if (!invertible(viewProjection) || !invertible(d.camera.projection)) return fail("the camera's view-projection is not invertible");
    if (!invertible(previousViewProjection)) return fail("the previous camera's view-projection is not invertible");
    if (!detail::finite(d.gbuffer.normalsUnpackScale) || !detail::finite(d.gbuffer.normalsUnpackOffset)) return fail("the normals' unpack scale and offset must be finite");
    if (!detail::finite(d.gbuffer.motionVectorScale)) return fail("motionVectorScale must be finite");
    if (!(d.roughnessThreshold >= 0.0f && d.roughnessThreshold <= 1.0f)) return fail("roughnessThreshold " + std::to_string(d.roughnessThreshold) + " is outside 0..1");
    if (!(d.sdfRoughnessThreshold >= 0.0f && d.sdfRoughnessThreshold <= 1.0f))
        return fail("sdfRoughnessThreshold " + std::to_string(d.sdfRoughnessThreshold) + " is outside 0..1");
    if (d.samplesPerQuad != 1 && d.samplesPerQuad != 2 && d.samplesPerQuad != 4)
        return fail("samplesPerQuad " + std::to_string(d.samplesPerQuad) + " is not 1, 2 or 4");
    if (!(d.hybridMissWeight >= 0.0f) || !std::isfinite(d.hybridMissWeight)) return fail("hybridMissWeight must be a finite number ≥ 0");
    if (!(d.hybridSpawnRate >= 0.0f && d.hybridSpawnRate <= 1.0f)) return fail("hybridSpawnRate " + std::to_string(d.hybridSpawnRate) + " is outside 0..1");

    ReflectionParams p{};
    std::memcpy(&p, lastParams_.data(), sizeof(p));  // keeps the trace's and the debug view's sections
    p.inverseViewProjection = glm::inverse(viewProjection);
    p.viewProjection = viewProjection;
    p.previousViewProjection = previousViewProjection;
    p.inverseProjection = glm::inverse(d.camera.projection);
    p.normalScale = glm::vec4(d.gbuffer.normalsUnpackScale, d.roughnessThreshold);
    p.normalBias = glm::vec4(d.gbuffer.normalsUnpackOffset, d.sdfRoughnessThreshold);
    p.hybrid = glm::vec4(d.hybridMissWeight, d.hybridSpawnRate, d.gbuffer.motionVectorScale);
    p.size = glm::uvec4(width_, height_, tilesX(), tilesY());
    p.options = glm::uvec4(d.samplesPerQuad, d.gbuffer.roughnessChannel, d.gbuffer.roughnessPerceptual ? 1u : 0u, d.camera.reversedDepth ? 1u : 0u);
    p.options2 = glm::uvec4(d.useHitCounter ? 1u : 0u, d.useScreenSpace ? 1u : 0u, d.useSdf ? 1u : 0u, d.gbuffer.motionVectors ? 1u : 0u);
    p.frame = glm::uvec4(d.frameIndex, 0u, 0u, 0u);
    device_.beginMarker("parameters");
    const bool paramsOk = writeParams(&p, 0, offsetof(ReflectionParams, trace));
    device_.endMarker();
    if (!paramsOk) return fail("the device refused the parameters (see its messages)", ErrorCode::DeviceFailure);

    const rhi::TextureHandle history = hitCounters_[current_], written = hitCounters_[current_ ^ 1u];
    rhi::DispatchState s;
    s.shader = classify_;
    s.label = "classify reflections";
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
    s.bindings.textures.push(rhi::TextureBinding{0, rhi::wholeTexture(d.gbuffer.depth), point_});
    s.bindings.textures.push(rhi::TextureBinding{1, rhi::wholeTexture(d.gbuffer.normals), point_});
    s.bindings.textures.push(rhi::TextureBinding{2, rhi::wholeTexture(d.gbuffer.roughness), point_});
    s.bindings.textures.push(rhi::TextureBinding{3, rhi::wholeTexture(d.gbuffer.motionVectors ? d.gbuffer.motionVectors : noMotion_), point_});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{0, screenList_, {}, rhi::Access::Write});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{1, sdfList_, {}, rhi::Access::Write});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{2, denoiseList_, {}, rhi::Access::Write});
    // The counts this classification adds to were zeroed by the previous one, which this one zeroes for the next: no
    // clear and barrier ahead of the pass.
    const uint32_t counting = countIndex_ ^ 1u;
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{3, counts_[counting], {}, rhi::Access::Atomic});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{4, counts_[countIndex_], {}, rhi::Access::Write});
    s.bindings.storageImages.push(rhi::storageImage(0, history, rhi::Access::Read));
    s.bindings.storageImages.push(rhi::storageImage(1, written, rhi::Access::Write));
    s.bindings.storageImages.push(rhi::storageImage(2, tileInfo_, rhi::Access::Write));
    s.bindings.storageImages.push(rhi::storageImage(3, tileStats_, rhi::Access::Write));
    // 4 × 4 tiles per group (classify_reflections.comp).
    if (!device_.dispatch(s, (tilesX() + 3) / 4, (tilesY() + 3) / 4, 1)) return fail("the device refused the classification (see its messages)", ErrorCode::DeviceFailure);
    countIndex_ = counting;
    if (!recordArgs()) return fail("the device refused the arguments pass (see its messages)", ErrorCode::DeviceFailure);
    current_ ^= 1u;
    depth_ = d.gbuffer.depth;
    normals_ = d.gbuffer.normals;
    roughness_ = d.gbuffer.roughness;
    classified_ = true;
    traced_ = false;
    return true;
}

bool ReflectionClassifier::recordArgs() {
    rhi::DispatchState s;
    s.shader = args_;
    s.label = "reflection dispatch arguments";
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{0, rayCounts(), {}, rhi::Access::ReadWrite});
    return device_.dispatch(s, 1, 1, 1);
}

ReflectionClassifyCounts ReflectionClassifier::readCounts() {
    uint32_t w[kReflectionCountWords] = {};
    ReflectionClassifyCounts c;
    const size_t tiles = size_t(tilesX()) * tilesY();
    std::vector<uint32_t> info(tiles), stats(tiles);
    if (!device_.readBuffer(rayCounts(), 0, sizeof(w), w) || !device_.readTexture(tileInfo_, {}, info.data()) ||
        !device_.readTexture(tileStats_, {}, stats.data()))
        return c;
    c.screenEntries = w[9];
    c.sdfRays = w[11];
    c.denoiseTiles = w[12];
    uint32_t classifiedSdf = 0, sdfAfterTrace = 0;
    for (size_t t = 0; t < tiles; ++t) {
        const uint32_t i = info[t], st = stats[t];
        uint32_t* perClass[3] = {&c.screenSpaceFirstTiles, &c.checkerboardTiles, &c.sdfOnlyTiles};
        if ((i & 3u) < 3u) ++*perClass[i & 3u];
        c.screenRays += (i >> 8) & 0xFFu;
        sdfAfterTrace += (i >> 16) & 0xFFu;
        c.screenHits += i >> 24;
        c.surfacePixels += st & 0xFFu;
        c.glossyPixels += (st >> 8) & 0xFFu;
        classifiedSdf += (st >> 16) & 0xFFu;
        c.rayPixels += st >> 24;
    }
    c.screenMisses = sdfAfterTrace - classifiedSdf;  // what the trace appended
    return c;
}

MemoryUse ReflectionClassifier::memoryUse() const { return detail::MemoryTally(device_).add(screenList_).add(sdfList_).add(denoiseList_).add(counts_[0]).add(counts_[1]).add(params_).add(hitCounters_[0]).add(hitCounters_[1]).add(tileInfo_).add(tileStats_).add(noMotion_).use(); }

}  // namespace bricklight::reflections
