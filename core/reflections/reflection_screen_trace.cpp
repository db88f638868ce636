// The reflection classifier's screen-space trace (shaders/reflections/trace_reflections_screen.comp, then the
// arguments pass again for the SDF list it grew) and its debug view (reflection_debug.comp).
// include/bricklight/reflections/classifier.h, docs/reflections.md.
#include <cmath>

#include "bricklight/reflections/classifier.h"
#include "reflection_params.h"
#include "../common/refusal.h"

namespace bricklight::reflections {

bool ReflectionClassifier::traceScreenSpace(const ReflectionTraceDesc& d, Error* error) {
    const bricklight::detail::Refusal fail(error, "reflection classifier");
    if (!classified_ || !device_.describe(depth_) || !device_.describe(normals_) || !device_.describe(roughness_))
        return fail("traceScreenSpace() needs a classify() whose depth, normals and roughness are still live", ErrorCode::InvalidState);
    // A second trace would list the same misses again and count them twice in the tile counters.
    if (traced_) return fail("traceScreenSpace() runs once per classify()", ErrorCode::InvalidState);
    const rhi::TextureDesc* pyramid = d.depthPyramid ? device_.describe(d.depthPyramid) : nullptr;
    if (!pyramid) return fail("depthPyramid is missing or not a live texture", ErrorCode::MissingInput);
    if (pyramid->format != rhi::Format::RG32_FLOAT || pyramid->dimension != rhi::TextureDimension::Texture2D ||
        !(pyramid->usage & rhi::TextureUsage::Sampled) || pyramid->width != width_ || pyramid->height != height_)
        return fail("depthPyramid '" + pyramid->debugName + "' must be a sampled 2D RG32_FLOAT texture of " + std::to_string(width_) + "x" +
                    std::to_string(height_) + " at mip 0", ErrorCode::WrongFormat);
    const rhi::TextureDesc* lit = d.previousLit ? device_.describe(d.previousLit) : nullptr;
    if (!lit) return fail("previousLit is missing or not a live texture", ErrorCode::MissingInput);
    using Kind = rhi::FormatInfo::Kind;
    const rhi::FormatInfo& litFormat = rhi::formatInfo(lit->format);
    if (lit->dimension != rhi::TextureDimension::Texture2D || !(lit->usage & rhi::TextureUsage::Sampled) || litFormat.channels < 3 ||
        (litFormat.kind != Kind::Float && litFormat.kind != Kind::Unorm && litFormat.kind != Kind::Srgb && litFormat.kind != Kind::PackedFloat))
        return fail("previousLit '" + lit->debugName + "' must be a sampled 2D texture of 3 or 4 float or unorm channels, not " + litFormat.name, ErrorCode::WrongFormat);
    const rhi::TextureDesc* out = d.output ? device_.describe(d.output) : nullptr;
    if (!out) return fail("output is missing or not a live texture", ErrorCode::MissingInput);
    if (out->format != rhi::Format::RGBA16_FLOAT || out->dimension != rhi::TextureDimension::Texture2D || !(out->usage & rhi::TextureUsage::Storage) ||
        out->width != width_ || out->height != height_)
        return fail("output '" + out->debugName + "' must be a 2D RGBA16_FLOAT texture with Storage usage of " + std::to_string(width_) + "x" +
                    std::to_string(height_), ErrorCode::WrongFormat);
    if (d.output == d.previousLit) return fail("output and previousLit must be different textures");
    if (d.maxIterations < 1 || d.maxIterations > 1024) return fail("maxIterations " + std::to_string(d.maxIterations) + " is outside 1..1024");
    if (!(d.thickness > 0.0f) || !std::isfinite(d.thickness)) return fail("thickness must be a finite number > 0 (a fraction of the distance from the camera)");
    if (!(d.edgeFade >= 0.0f && d.edgeFade < 0.5f)) return fail("edgeFade " + std::to_string(d.edgeFade) + " is outside 0..0.5");
    if (!(d.confidenceThreshold >= 0.0f && d.confidenceThreshold <= 1.0f))
        return fail("confidenceThreshold " + std::to_string(d.confidenceThreshold) + " is outside 0..1");

    struct {
        glm::uvec4 trace;
        glm::vec4 trace2;
    } section{glm::uvec4(d.maxIterations, pyramid->mipLevels, 0u, 0u), glm::vec4(d.thickness, d.edgeFade, d.confidenceThreshold, 0.0f)};
    static_assert(sizeof(section) == offsetof(ReflectionParams, debug) - offsetof(ReflectionParams, trace));
    if (!writeParams(&section, offsetof(ReflectionParams, trace), sizeof(section))) return fail("the device refused the parameters (see its messages)", ErrorCode::DeviceFailure);
    // Texels without a resolved ray read a = 0 (the pass writes only the resolved ones).
    device_.beginMarker("clear");
    {
        rhi::DispatchState s;
        s.shader = clear_;
        s.label = "reflection output clear";
        s.bindings.storageImages.push(rhi::storageImage(0, d.output, rhi::Access::Write, 0));
        device_.dispatch(s, (width_ + 15) / 16, (height_ + 15) / 16, 1);
    }
    device_.endMarker();
    rhi::DispatchState s;
    s.shader = trace_;
    s.label = "trace screen-space reflections";
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{1, screenList_, {}});
    s.bindings.textures.push(rhi::TextureBinding{0, rhi::wholeTexture(depth_), point_});
    s.bindings.textures.push(rhi::TextureBinding{1, rhi::wholeTexture(normals_), point_});
    s.bindings.textures.push(rhi::TextureBinding{2, rhi::wholeTexture(roughness_), point_});
    s.bindings.textures.push(rhi::TextureBinding{3, rhi::wholeTexture(d.depthPyramid), point_});
    s.bindings.textures.push(rhi::TextureBinding{4, rhi::wholeTexture(d.previousLit), linear_});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{0, sdfList_, {}, rhi::Access::Write});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{1, rayCounts(), {}, rhi::Access::Atomic});
    s.bindings.storageImages.push(rhi::storageImage(0, d.output, rhi::Access::Write));
    s.bindings.storageImages.push(rhi::storageImage(1, hitCounters_[current_], rhi::Access::Atomic));
    s.bindings.storageImages.push(rhi::storageImage(2, tileInfo_, rhi::Access::Atomic));
    if (!device_.dispatchIndirect(s, rayCounts(), kReflectionArgsScreenTrace)) return fail("the device refused the trace (see its messages)", ErrorCode::DeviceFailure);
    if (!recordArgs()) return fail("the device refused the arguments pass (see its messages)", ErrorCode::DeviceFailure);
    traced_ = true;
    return true;
}

bool ReflectionClassifier::debugView(rhi::TextureHandle output, ReflectionDebugMode mode, Error* error) {
    const bricklight::detail::Refusal fail(error, "reflection classifier");
    const rhi::TextureDesc* out = output ? device_.describe(output) : nullptr;
    if (!out || out->format != rhi::Format::RGBA8_UNORM || out->dimension != rhi::TextureDimension::Texture2D ||
        !(out->usage & rhi::TextureUsage::Storage) || out->width != width_ || out->height != height_)
        return fail("the debug view's output must be a live 2D RGBA8_UNORM texture with Storage usage of " + std::to_string(width_) + "x" +
                    std::to_string(height_), ErrorCode::WrongFormat);
    if (mode != ReflectionDebugMode::TileClass && mode != ReflectionDebugMode::RaysPerTile && mode != ReflectionDebugMode::HitCounter)
        return fail("debug mode " + std::to_string(uint32_t(mode)) + " is not TileClass, RaysPerTile or HitCounter");
    if (!classified_) return fail("debugView() needs a classify() first", ErrorCode::InvalidState);
    const glm::uvec4 section(uint32_t(mode), 0u, 0u, 0u);
    if (!writeParams(&section, offsetof(ReflectionParams, debug), sizeof(section))) return fail("the device refused the parameters (see its messages)", ErrorCode::DeviceFailure);
    rhi::DispatchState s;
    s.shader = debug_;
    s.label = "reflection classifier debug view";
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{0, params_, {}});
    s.bindings.storageImages.push(rhi::storageImage(0, tileInfo_, rhi::Access::Read));
    s.bindings.storageImages.push(rhi::storageImage(1, hitCounters_[current_], rhi::Access::Read));
    s.bindings.storageImages.push(rhi::storageImage(2, output, rhi::Access::Write));
    if (!device_.dispatch(s, (width_ + 7) / 8, (height_ + 7) / 8, 1)) return fail("the device refused the debug view (see its messages)", ErrorCode::DeviceFailure);
    return true;
}

}  // namespace bricklight::reflections
