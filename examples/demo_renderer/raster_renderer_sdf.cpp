// The renderer's distance field (docs/sdf.md) and the one place it is updated each frame, with the GI's alpha pass
// right after: the field serves hybrid shadows' rays, the SDF GI and cones stopped by the field.
//
// Alpha-tested geometry (RasterOptions::foliage; docs/gi.md, "Foliage"): the cards are registered in the distance
// field as alpha-tested, the GI context keeps an alpha cache, and each frame, after the field's update and before
// any pass that reads it, the alpha pass draws the scene's vertex buffer through gi::GiContext::alphaPassState with
// render/alpha_pass.vert (only alpha-tested materials' triangles survive) and render/alpha_pass.frag (the G-buffer's
// alpha test).
#include "raster_renderer.h"

namespace bricklight::render {

// The diffuse share of the base colour (textures are not averaged: their factor stands for them) and the emission.
sdf::SurfaceMaterial fieldMaterialOf(const scenes::TriangleMesh& mesh) {
    return sdf::SurfaceMaterial{
        glm::clamp(mesh.albedo * (1.0f - mesh.metalness) * (1.0f - mesh.transmission), glm::vec3(0.0f), glm::vec3(1.0f)), mesh.emission};
}

bool RasterRenderer::createSdf(const scenes::SceneGeometry& scene, std::string* error) {
    auto fail = [&](const std::string& m) {
        if (error) *error = "raster renderer: " + m;
        return false;
    };
    const glm::vec3 extent = scene.boundsMax - scene.boundsMin;
    const float side = std::max(extent.x, std::max(extent.y, extent.z));
    sdf::SceneDesc sd;
    sd.cascadeCount = options_.sdfCascades;
    // The finest cascade holds the whole scene with a margin; coarser ones catch rays that leave it.
    sd.finestVoxelSize = sdf::suggestVoxelSize(side * 1.1f, 1);
    // Hybrid shadows: finer cascades in front, centred on the camera (raster_renderer_shadows.cpp).
    const uint32_t finer = hybridShadowFinerCascades();
    sd.cascadeCount += finer;
    sd.finestVoxelSize /= float(1u << finer);
    sd.budgets = options_.sdfBudgets;
    sd.debugName = "render sdf";
    sd.errorCallback = options_.errorCallback;
    Error why;
    sdf_ = sdf::SdfScene::create(device_, sd, &why);
    if (!sdf_) return fail("the distance field for GI: " + why.message);
    std::vector<sdf::MeshHandle> meshes;
    for (const scenes::TriangleMesh& m : scene.meshes) {
        if (m.deforming) {
            // Rewritten every frame (syncSdf): our own buffers, given to the field as the application's.
            DeformingMesh d;
            d.mesh = uint32_t(&m - scene.meshes.data());
            d.positions = device_.createBuffer({m.positions.size() * 4, 0, rhi::BufferUsage::ShaderRead, m.name + " positions"}, m.positions.data());
            d.indices = device_.createBuffer({m.indices.size() * 4, 0, rhi::BufferUsage::ShaderRead, m.name + " indices"}, m.indices.data());
            if (!d.positions || !d.indices) return fail("could not create the buffers of deforming mesh '" + m.name + "'");
            sdfDeforming_.push_back(d);
            sdf::MeshBuffers b;
            b.vertexBuffer = d.positions;
            b.vertexCount = uint32_t(m.positions.size() / 3);
            b.indexBuffer = d.indices;
            b.triangleCount = m.triangleCount();
            b.boundsMin = m.deformingBoundsMin;
            b.boundsMax = m.deformingBoundsMax;
            b.name = m.name;
            meshes.push_back(sdf_->createMesh(b));
            if (!meshes.back()) return fail("the distance field rejected mesh '" + m.name + "': " + sdf_->lastError().message);
            continue;
        }
        sdf::MeshArrays a;
        a.positions = m.positions.data();
        a.vertexCount = uint32_t(m.positions.size() / 3);
        a.indices = m.indices.data();
        a.indexCount = uint32_t(m.indices.size());
        a.name = m.name;
        meshes.push_back(sdf_->createMesh(a));
        if (!meshes.back()) return fail("the distance field rejected mesh '" + m.name + "': " + sdf_->lastError().message);
    }
    for (const scenes::MeshInstance& i : scene.instances) {
        const bool alphaTested = scene.meshes[i.mesh].alphaTested();
        sdfTransforms_.push_back(i.transform);
        if (alphaTested && options_.foliage == FoliageMode::LeftOut) {
            sdfInstances_.push_back({});  // not in the field (setScene skips it)
            continue;
        }
        sdf::InstanceDesc id;
        id.mesh = meshes[i.mesh];
        id.transform = i.transform;
        id.alphaTested = alphaTested && options_.foliage == FoliageMode::AlphaAware;
        id.dynamic = i.dynamic;
        id.material = fieldMaterialOf(scene.meshes[i.mesh]);
        sdfInstances_.push_back(sdf_->addInstance(id));
        if (!sdfInstances_.back()) return fail("the distance field rejected an instance: " + sdf_->lastError().message);
    }
    sdfCenter_ = sceneCenter_ = 0.5f * (scene.boundsMin + scene.boundsMax);
    return true;
}

void RasterRenderer::syncSdf(const scenes::SceneGeometry& scene) {
    if (!sdf_) return;
    for (const DeformingMesh& d : sdfDeforming_) {
        const std::vector<float>& p = scene.meshes[d.mesh].positions;
        device_.writeBuffer(d.positions, 0, p.data(), p.size() * 4);
    }
    for (size_t i = 0; i < scene.instances.size() && i < sdfInstances_.size(); ++i)
        if (sdfInstances_[i] && scene.instances[i].transform != sdfTransforms_[i]) {
            sdf_->setTransform(sdfInstances_[i], scene.instances[i].transform);
            sdfTransforms_[i] = scene.instances[i].transform;
        }
}

// Once a frame, before the first pass that reads the field: hybrid shadows' finer cascades follow the camera,
// otherwise the field stays centred on the scene.
void RasterRenderer::updateDistanceField() {
    const bool hybridShadows = options_.shadows == ShadowMode::Hybrid;
    if (!sdf_ || !(gi_ || hybridShadows || (coneTracer_ && options_.vctSdfOcclusion))) return;
    device_.beginMarker("sdf update");
    sdf_->update(hybridShadows && hybridShadowFinerCascades() > 0 ? camera_.eye : sdfCenter_);
    device_.endMarker();
    if (gi_) runAlphaPass();  // GI's rays and hybrid shadows' read this frame's coverage (the bricks may have moved)
}

bool RasterRenderer::alphaAwareFoliage() const { return options_.foliage == FoliageMode::AlphaAware && scene_->hasAlphaTested(); }

bool RasterRenderer::createAlphaPass(std::string* error) {
    auto shader = [&](const char* name) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader(name);
        return sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
    };
    alphaPassVertex_ = shader("render/alpha_pass.vert");
    alphaPassFragment_ = shader("render/alpha_pass.frag");
    if (alphaPassVertex_ && alphaPassFragment_) return true;
    if (error) *error = "raster renderer: the device could not create the GI's alpha pass shaders";
    return false;
}

void RasterRenderer::runAlphaPass() {
    if (!alphaPassFragment_) return;
    Error why;
    std::optional<rhi::DrawCallState> state = gi_->alphaPassState(alphaPassFragment_, &why);
    if (!state) return;  // reported through the GI's error callback
    state->label = "gi alpha pass";
    state->vertexShader = alphaPassVertex_;
    rhi::DrawArgs args;
    scene_->bindAlphaPass(*state, &args);
    device_.beginMarker("gi alpha pass");
    device_.draw(*state, args);
    device_.endMarker();
}

}  // namespace bricklight::render
