// Checks of one frame's inputs before anything is recorded: every message names the input (and its debug
// name) and the problem, and a failed check records nothing.
#include <cmath>
#include <utility>

#include "bricklight/vct.h"
#include "../common/finite_checks.h"
#include "gi_context_impl.h"

namespace bricklight::gi::detail {

namespace {

bool invertible(const glm::mat4& m) {
    const float d = glm::determinant(m);
    return std::isfinite(d) && std::fabs(d) > 1e-30f;
}

}  // namespace

bool GiContextImpl::checkInputs(const DispatchDesc& d) {
    const uint32_t dw = desc_.displayWidth, dh = desc_.displayHeight;
    const std::string displaySize = std::to_string(dw) + "x" + std::to_string(dh);
    using K = rhi::FormatInfo::Kind;
    // A texture input: live, sampled, 2D, display-sized when `display`, with at least `channels` float
    // (or unorm/depth) channels.
    auto input = [&](const char* what, rhi::TextureHandle t, uint32_t channels, bool display) -> bool {
        if (!t) return fail(ErrorCode::MissingInput, std::string("dispatch: input '") + what + "' is missing");
        const rhi::TextureDesc* td = device_.describe(t);
        if (!td) return fail(ErrorCode::InvalidHandle, std::string("dispatch: input '") + what + "' is not a live texture");
        const std::string name = std::string("dispatch: input '") + what + "' (texture '" + td->debugName + "')";
        if (td->dimension != rhi::TextureDimension::Texture2D) return fail(ErrorCode::WrongFormat, name + " must be a 2D texture");
        if (!(td->usage & rhi::TextureUsage::Sampled)) return fail(ErrorCode::WrongFormat, name + " was not created with Sampled usage");
        const rhi::FormatInfo& fi = rhi::formatInfo(td->format);
        if (fi.kind == K::Uint || fi.kind == K::Sint || fi.kind == K::None)
            return fail(ErrorCode::WrongFormat, name + " has format " + fi.name + "; it must be a float, unorm or depth format");
        if (fi.channels < channels)
            return fail(ErrorCode::WrongFormat, name + " has format " + fi.name + " with " + std::to_string(fi.channels) + " channel(s); it needs " +
                        std::to_string(channels));
        if (display && (td->width != dw || td->height != dh))
            return fail(ErrorCode::WrongSize, name + " is " + std::to_string(td->width) + "x" + std::to_string(td->height) +
                        "; it must be the display size " + displaySize);
        return true;
    };
    auto output = [&](const char* what, rhi::TextureHandle t) -> bool {
        if (!t) return fail(ErrorCode::MissingInput, std::string("dispatch: output '") + what + "' is missing");
        const rhi::TextureDesc* td = device_.describe(t);
        if (!td) return fail(ErrorCode::InvalidHandle, std::string("dispatch: output '") + what + "' is not a live texture");
        const std::string name = std::string("dispatch: output '") + what + "' (texture '" + td->debugName + "')";
        if (td->dimension != rhi::TextureDimension::Texture2D || td->format != rhi::Format::RGBA16_FLOAT)
            return fail(ErrorCode::WrongFormat, name + " must be a 2D RGBA16_FLOAT texture, not " + rhi::formatName(td->format));
        if (!(td->usage & rhi::TextureUsage::Storage)) return fail(ErrorCode::WrongFormat, name + " was not created with Storage usage");
        if (td->width != dw || td->height != dh)
            return fail(ErrorCode::WrongSize, name + " is " + std::to_string(td->width) + "x" + std::to_string(td->height) + "; it must be " + displaySize);
        return true;
    };
    if (!input("depth", d.gbuffer.depth, 1, true) || !input("normals", d.gbuffer.normals, 3, true) || !input("roughness", d.gbuffer.roughness, 1, true) ||
        !input("previousLitOutput", d.previousLitOutput, 3, false))
        return false;
    if (d.gbuffer.motionVectors && !input("motionVectors", d.gbuffer.motionVectors, 2, true)) return false;
    {  // depth is one channel of device depth: a colour texture here is a G-buffer target bound by mistake
        const rhi::TextureDesc* td = device_.describe(d.gbuffer.depth);
        const rhi::FormatInfo& fi = rhi::formatInfo(td->format);
        if (fi.channels != 1 || (fi.kind != K::Float && fi.kind != K::Depth))
            return fail(ErrorCode::WrongFormat, "dispatch: input 'depth' (texture '" + td->debugName + "') has format " + fi.name +
                                                    "; it must hold one channel of device depth (D32_FLOAT, R32_FLOAT or R16_FLOAT)");
    }
    if (d.diffuseAlbedo && !input("diffuseAlbedo", d.diffuseAlbedo, 3, true)) return false;
    if (d.emission && !d.diffuseAlbedo) return fail(ErrorCode::MissingInput, "dispatch: input 'emission' is given without 'diffuseAlbedo': relighting needs the albedo");
    if (d.emission && !input("emission", d.emission, 3, true)) return false;
    if (!checkLights(d)) return false;
    const rhi::FormatInfo& roughness = rhi::formatInfo(device_.describe(d.gbuffer.roughness)->format);
    if (d.gbuffer.roughnessChannel >= roughness.channels)
        return fail(ErrorCode::WrongFormat, "dispatch: roughnessChannel " + std::to_string(d.gbuffer.roughnessChannel) + " is not a channel of the roughness texture (" +
                    roughness.name + ")");
    if (!output("outputDiffuse", d.outputDiffuse)) return false;
    if (!(desc_.flags & ContextFlags::NoSpecular) || d.outputSpecular)
        if (!output("outputSpecular", d.outputSpecular)) return false;
    if (d.outputSpecular && d.outputSpecular == d.outputDiffuse) return fail(ErrorCode::Aliasing, "dispatch: outputDiffuse and outputSpecular are the same texture");
    const std::pair<rhi::TextureHandle, const char*> inputs[] = {
        {d.gbuffer.depth, "depth"}, {d.gbuffer.normals, "normals"}, {d.gbuffer.roughness, "roughness"}, {d.gbuffer.motionVectors, "motionVectors"},
        {d.previousLitOutput, "previousLitOutput"}, {d.diffuseAlbedo, "diffuseAlbedo"}, {d.emission, "emission"}};
    for (const auto& [in, inName] : inputs)
        for (const auto& [out, outName] : {std::pair{d.outputDiffuse, "outputDiffuse"}, std::pair{d.outputSpecular, "outputSpecular"}})
            if (in && in == out)
                return fail(ErrorCode::Aliasing, std::string("dispatch: texture '") + device_.describe(in)->debugName + "' is bound as output '" +
                                                     outName + "' and as input '" + inName + "'");
    if (d.unseenLight && d.unseenLight->desc().emittance == vct::EmittanceMode::None)
        return fail(ErrorCode::InvalidArgument, "dispatch: unseenLight is a clip-map without emittance (EmittanceMode::None): it holds no light");
    if (d.environmentKind != EnvironmentKind::None) {
        if (!d.environmentMap) return fail(ErrorCode::MissingInput, "dispatch: environmentKind is set but environmentMap is missing");
        const rhi::TextureDesc* td = device_.describe(d.environmentMap);
        if (!td) return fail(ErrorCode::InvalidHandle, "dispatch: environmentMap is not a live texture");
        const std::string name = "dispatch: environmentMap (texture '" + td->debugName + "')";
        const bool cube = d.environmentKind == EnvironmentKind::Cube;
        if (cube && td->dimension != rhi::TextureDimension::TextureCube) return fail(ErrorCode::WrongFormat, name + " must be a cube texture (environmentKind Cube)");
        if (!cube && td->dimension != rhi::TextureDimension::Texture2D)
            return fail(ErrorCode::WrongFormat, name + " must be a 2D texture (environmentKind Equirectangular)");
        if (!(td->usage & rhi::TextureUsage::Sampled)) return fail(ErrorCode::WrongFormat, name + " was not created with Sampled usage");
        const rhi::FormatInfo& fi = rhi::formatInfo(td->format);
        if (fi.kind == K::Uint || fi.kind == K::Sint || fi.kind == K::Depth || fi.channels < 3)
            return fail(ErrorCode::WrongFormat, name + " has format " + fi.name + "; it needs an RGB float, unorm or sRGB format");
        if (!(d.environmentIntensity >= 0.0f) || !std::isfinite(d.environmentIntensity))
            return fail(ErrorCode::InvalidArgument, "dispatch: environmentIntensity must be finite and >= 0");
    }
    if (uint32_t(d.environmentKind) > uint32_t(EnvironmentKind::Equirectangular)) return fail(ErrorCode::InvalidArgument, "dispatch: unknown environmentKind");
    for (const auto& [m, what] : {std::pair{&d.camera.view, "view"}, std::pair{&d.camera.projection, "projection"},
                                  std::pair{&d.camera.previousView, "previousView"}, std::pair{&d.camera.previousProjection, "previousProjection"}})
        if (!bricklight::detail::finite(*m) || !invertible(*m)) return fail(ErrorCode::InvalidArgument, std::string("dispatch: matrix '") + what + "' is not finite and invertible");
    if (!std::isfinite(d.cameraPosition.x) || !std::isfinite(d.cameraPosition.y) || !std::isfinite(d.cameraPosition.z))
        return fail(ErrorCode::InvalidArgument, "dispatch: cameraPosition is not finite");
    for (float v : {d.gbuffer.normalsUnpackScale.x, d.gbuffer.normalsUnpackScale.y, d.gbuffer.normalsUnpackScale.z, d.gbuffer.normalsUnpackOffset.x,
                    d.gbuffer.normalsUnpackOffset.y, d.gbuffer.normalsUnpackOffset.z, d.gbuffer.motionVectorScale.x, d.gbuffer.motionVectorScale.y, d.roughnessThreshold})
        if (!std::isfinite(v)) return fail(ErrorCode::InvalidArgument, "dispatch: normal unpack, motion vector scale and roughnessThreshold must be finite");
    const TraceParams& t = d.trace;
    const uint32_t cascades = scene_.desc().cascadeCount;
    if (t.startCascade >= cascades) return fail(ErrorCode::InvalidArgument, "dispatch: trace.startCascade " + std::to_string(t.startCascade) +
                                                " is beyond the scene's " + std::to_string(cascades) + " cascades");
    if (t.endCascade < t.startCascade) return fail(ErrorCode::InvalidArgument, "dispatch: trace.endCascade is below trace.startCascade");
    for (float v : {t.rayPushOff, t.specularRayPushOff, t.tMin})
        if (!(v >= 0.0f) || !std::isfinite(v)) return fail(ErrorCode::InvalidArgument, "dispatch: trace push-offs and tMin must be finite and >= 0");
    if (!(t.tMax > t.tMin)) return fail(ErrorCode::InvalidArgument, "dispatch: trace.tMax must be greater than trace.tMin");
    if (!(t.epsilonScale > 0.0f) || !(t.specularEpsilonScale > 0.0f) || !std::isfinite(t.epsilonScale) ||
        !std::isfinite(t.specularEpsilonScale))
        return fail(ErrorCode::InvalidArgument, "dispatch: trace epsilon scales must be finite and > 0");
    if (!(t.coarsenAfterVoxels >= 0.0f) || !std::isfinite(t.coarsenAfterVoxels))
        return fail(ErrorCode::InvalidArgument, "dispatch: trace.coarsenAfterVoxels must be finite and >= 0");
    if (t.maxIterationsPerCascade == 0 || t.maxIterationsPerCascade > kMaxTraceIterations)
        return fail(ErrorCode::InvalidArgument, "dispatch: trace.maxIterationsPerCascade " + std::to_string(t.maxIterationsPerCascade) + " is outside 1.." +
                    std::to_string(kMaxTraceIterations));
    return true;
}

bool GiContextImpl::checkLights(const DispatchDesc& d) {
    if (d.emittersInLights && d.previousLitIncludesEmission)
        return fail(ErrorCode::InvalidArgument, "dispatch: emittersInLights needs previousLitIncludesEmission = false (the cache would count the emission twice)");
    if (d.lightUnseenSurfaces && !d.diffuseAlbedo)
        return fail(ErrorCode::MissingInput, "dispatch: lightUnseenSurfaces is set without 'diffuseAlbedo': relighting needs the albedo");
    if (d.lightCount == 0) return true;
    if (!d.lights) return fail(ErrorCode::MissingInput, "dispatch: lightCount is " + std::to_string(d.lightCount) + " but lights is null");
    if (d.lightCount > kMaxLights)
        return fail(ErrorCode::OverBudget, "dispatch: lightCount " + std::to_string(d.lightCount) + " is above kMaxLights (" + std::to_string(kMaxLights) + ")");
    if (!d.diffuseAlbedo) return fail(ErrorCode::MissingInput, "dispatch: lights are given without 'diffuseAlbedo': relighting needs the albedo");
    auto finite3 = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    for (uint32_t i = 0; i < d.lightCount; ++i) {
        const Light& l = d.lights[i];
        const std::string name = "dispatch: lights[" + std::to_string(i) + "]";
        if (uint32_t(l.type) > uint32_t(LightType::Triangle)) return fail(ErrorCode::InvalidArgument, name + " has an unknown type");
        if (!finite3(l.position) || !finite3(l.direction) || !finite3(l.color) || !std::isfinite(l.spotInnerAngle) ||
            !std::isfinite(l.spotOuterAngle) || !finite3(l.edge0) || !finite3(l.edge1))
            return fail(ErrorCode::InvalidArgument, name + " has a value that is not finite");
        if (l.color.x < 0.0f || l.color.y < 0.0f || l.color.z < 0.0f) return fail(ErrorCode::InvalidArgument, name + " has a negative color");
        const bool area = l.type == LightType::Rect || l.type == LightType::Triangle;
        if (area) {
            const float scale = std::max(glm::length(l.edge0), glm::length(l.edge1));
            if (!(glm::length(glm::cross(l.edge0, l.edge1)) > 1e-6f * scale * scale))  // also false for zero edges
                return fail(ErrorCode::InvalidArgument, name + " is an area light with no area (edge0 and edge1 zero or parallel)");
            continue;
        }
        if (l.type != LightType::Point && glm::length(l.direction) < 1e-6f) return fail(ErrorCode::InvalidArgument, name + " has a zero direction");
        if (l.type == LightType::Spot && !(l.spotInnerAngle >= 0.0f && l.spotInnerAngle <= l.spotOuterAngle && l.spotOuterAngle <= 3.1416f))
            return fail(ErrorCode::InvalidArgument, name + " needs 0 <= spotInnerAngle <= spotOuterAngle <= pi");
    }
    return true;
}

}  // namespace bricklight::gi::detail
