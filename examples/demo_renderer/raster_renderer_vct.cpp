// The fast path with voxel cone tracing (--gi vxgi, --ao vxao): the scene voxelized through
// vct::Clipmap::voxelizationState with the renderer's vertex shader and emittance (examples/demo_renderer/shaders/voxelize.vert,
// voxel_emittance.frag: its direct lighting, BVH-shadowed, times the diffuse albedo), then vct::ConeTracer into
// the same diffuse and specular outputs the SDF GI writes, so the composite is the same.
#include <algorithm>

#include "bricklight/half.h"
#include "raster_renderer.h"

namespace bricklight::render {

bool RasterRenderer::createVct(const scenes::SceneGeometry& scene, std::string* error) {
    auto fail = [&](const std::string& m) {
        if (error) *error = "raster renderer: voxel cone tracing: " + m;
        return false;
    };
    if (options_.vxao && options_.gi && options_.giTechnique == GiTechnique::Sdf)
        return fail("voxel AO with the SDF GI is not supported (both write the diffuse output): use --gi vxgi, whose diffuse alpha "
                    "is the AO, or --gi none");
    const glm::vec3 extent = scene.boundsMax - scene.boundsMin;
    const float side = std::max(extent.x, std::max(extent.y, extent.z));
    vct::ClipmapDesc desc;
    desc.resolution = options_.vctResolution;
    desc.levels = options_.vctLevels;
    const bool light = options_.gi && (options_.giTechnique == GiTechnique::Vct || options_.giUnseenFromVct);
    desc.emittance = light ? options_.vctEmittance : vct::EmittanceMode::None;
    options_.vctEmittance = desc.emittance;
    // With bounces the emittance holds last frame's indirect light, which changes every frame: revoxelize whole.
    desc.persistent = !options_.giFeedback;
    // ... reading the previous frame's atlas while writing the other.
    desc.multiBounce = options_.giFeedback && desc.emittance != vct::EmittanceMode::None;
    // The finest level holds the scene with a margin (the anchor snaps to even voxels: two voxels each side).
    desc.finestVoxelSize = std::max(side * 1.1f, 1e-6f) / float(std::max(desc.resolution, 8u) - 4);
    if (options_.vctFinestVoxel > 0.0f) desc.finestVoxelSize = options_.vctFinestVoxel;
    Error why;
    if (options_.vctSdfOcclusion && !sdf_ && !createSdf(scene, error)) return false;
    clipmap_ = vct::Clipmap::create(device_, desc, &why);
    if (!clipmap_) return fail(why.message);
    // The SDF GI with the clip-map's light for unseen surfaces voxelizes only; it traces no cones.
    const bool traceCones = options_.vxao || (options_.gi && options_.giTechnique == GiTechnique::Vct);
    if (traceCones) {
        coneTracer_ = vct::ConeTracer::create(device_, *clipmap_, {options_.width, options_.height, options_.vctRefinementEntries}, &why);
        if (!coneTracer_) return fail(why.message);
    }
    if (probePixel_.x == ~0u) probePixel_ = glm::uvec2(options_.width / 2, options_.height / 2);
    if (!vct::checkConeTraceParams(options_.vctTrace, &why)) return fail(why.message);
    auto shader = [&](const char* name) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader(name);
        return sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
    };
    // Alpha-tested meshes (RasterOptions::foliage; docs/vct.md, "Foliage"): AlphaAware weighs their voxels' opacity
    // and light by their coverage (the hook in voxel_emittance.frag, voxel_coverage.frag); Opaque voxelizes them
    // without the hook, as solid cards; LeftOut drops their triangles in the vertex shader.
    const bool coverage = alphaAwareFoliage();
    const bool leftOut = options_.foliage == FoliageMode::LeftOut && scene_->hasAlphaTested();
    vctVertex_ = shader(leftOut ? "render/voxelize_solid_only.vert" : "render/voxelize.vert");
    // Without emittance (voxel AO) the fragment shader only weighs alpha-tested materials' opacity by their
    // coverage; without the hook to run, the clip-map's own opacity shader serves (voxelizeVct).
    const char* fragment = desc.emittance != vct::EmittanceMode::None
                               ? (coverage ? "render/voxel_emittance.frag" : "render/voxel_emittance_solid.frag")
                               : (coverage ? "render/voxel_coverage.frag" : nullptr);
    if (fragment) vctEmittance_ = shader(fragment);
    if (!vctVertex_ || (fragment && !vctEmittance_)) return fail("the device could not create the voxelization shaders");
    return true;
}

void RasterRenderer::voxelizeVct() {
    if (!clipmap_) return;
    device_.beginMarker("vct voxelize");
    Error why;
    if (!clipmap_->update(sceneCenter_, &why)) {
        if (options_.errorCallback) options_.errorCallback(rhi::Severity::Error, why.message);
        device_.endMarker();
        return;
    }
    if (!clipmap_->rewriteBoxes().empty()) {
        vct::VoxelMaterial material;
        material.twoSided = true;  // the renderer lights both sides of every surface, as the path tracer does
        material.thickness = options_.vctThickness;
        // Null for voxel AO without the coverage hook: the clip-map's own opacity shader.
        const bool lit = options_.vctEmittance != vct::EmittanceMode::None;
        material.fragmentShader = vctEmittance_;
        std::optional<rhi::DrawCallState> state = clipmap_->voxelizationState(material, &why);
        if (state) {
            state->label = "vct voxelize scene";
            state->vertexShader = vctVertex_;
            state->vertexInputs.push({0, rhi::VertexFormat::Float3, 0, 0});
            state->vertexInputs.push({1, rhi::VertexFormat::Float3, 0, 12});
            state->vertexInputs.push({2, rhi::VertexFormat::UInt1, 0, 24});
            state->vertexInputs.push({4, rhi::VertexFormat::Float2, 0, 40});
            state->vertexBuffers.push({scene_->vertexBuffer(), 0, GpuScene::kVertexStride, false});
            const glm::uvec4 lighting(options_.vctLightSamples, options_.giFeedback ? 1u : 0u, options_.vctSdfOcclusion ? 1u : 0u, 0u);
            const SceneLightConstants light = scene_->lightConstants(options_.seed, 1);
            if (material.fragmentShader) {  // the hooks' resources: materials and textures (coverage), lights, BVH
                state->bindings.constants.push(rhi::constants(1, light));
                scene_->bind(state->bindings, true);
            } else if (options_.foliage == FoliageMode::LeftOut && scene_->hasAlphaTested()) {
                state->bindings.readBuffers.push({2, scene_->materialBuffer(), {}});  // voxelize_solid_only.vert's
            }
            if (lit) {  // the emittance function's own (voxel AO has none)
                state->bindings.constants.push(rhi::constants(0, lighting));
                clipmap_->bounceBindings(state->bindings);  // blVoxelIndirect (bounces): the previous frame's light
            }
            rhi::DrawArgs args;
            args.vertexCount = 3 * rasterTriangleCount();  // glass is left out when the glass pass draws it
            device_.draw(*state, args);
        }
        clipmap_->finishVoxelization();
    }
    device_.endMarker();
}

void RasterRenderer::traceVct(bool cut) {
    if (!coneTracer_) return;
    Error why;
    vct::TraceDesc t;
    t.camera = frameCamera();
    t.gbuffer = frameGBuffer();
    t.cameraPosition = camera_.eye;
    t.outputDiffuse = giDiffuse_;
    t.outputSpecular = options_.vctEmittance == vct::EmittanceMode::None ? rhi::TextureHandle{} : giSpecular_;
    t.params = options_.vctTrace;
    t.occlusionField = options_.vctSdfOcclusion ? sdf_.get() : nullptr;
    t.resetHistory = cut;
    if (!coneTracer_->dispatch(t, &why) && options_.errorCallback) options_.errorCallback(rhi::Severity::Error, why.message);
}

Image RasterRenderer::readAmbientOcclusion() {
    Image img;
    if (!coneTracer_) return img;
    img.width = options_.width;
    img.height = options_.height;
    const size_t pixels = size_t(img.width) * img.height;
    std::vector<uint16_t> h(pixels * 4);
    device_.readTexture(giDiffuse_, {}, h.data());
    img.rgb.resize(pixels * 3);
    for (size_t i = 0; i < pixels; ++i) img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = halfToFloat(h[4 * i + 3]);
    return img;
}

Image RasterRenderer::vctDebugView(vct::DebugMode mode, float exposure) {
    Error why;
    const View view = View(uint32_t(View::VctOpacity) + uint32_t(mode));
    if (!clipmap_ || mode > vct::DebugMode::Rewritten || !drawDebugView(view, exposure, &why)) return {};
    return readDebugView();
}

Image RasterRenderer::vctConeSamplesView() {
    Error why;
    if (!coneTracer_ || !drawDebugView(View::VctConeSamples, 1.0f, &why)) {
        if (!why.message.empty() && options_.errorCallback) options_.errorCallback(rhi::Severity::Error, why.message);
        return {};
    }
    return readDebugView();
}

std::vector<vct::ConeSample> RasterRenderer::vctConeSamples() {
    return coneTracer_ ? coneTracer_->readConeSamples() : std::vector<vct::ConeSample>{};
}

uint32_t RasterRenderer::vctRefinedPixels() { return coneTracer_ ? coneTracer_->readRefinedPixels() : 0u; }

Image RasterRenderer::readDebugView() {
    Image img;
    std::vector<uint8_t> bytes(size_t(options_.width) * options_.height * 4);
    device_.readTexture(debugView_, {}, bytes.data());
    img.width = options_.width;
    img.height = options_.height;
    img.rgb.resize(size_t(img.width) * img.height * 3);
    for (size_t i = 0; i < img.rgb.size() / 3; ++i)
        for (int c = 0; c < 3; ++c) img.rgb[3 * i + size_t(c)] = float(bytes[4 * i + size_t(c)]) / 255.0f;
    return img;
}

}  // namespace bricklight::render
