// One GI frame as records. Ping-pong resources alternate with the frame index: [cur] is written this frame,
// [prev] holds last frame's. The passes keep docs/gi.md's numbers but are recorded by dependency level, so
// that passes with no hazard between them follow each other and a backend can run them between the same
// two barriers: 1+2 3 6 | 4 7 10 | 4b 5 9 | 8 8b 11 | 12 | 14 | 13 15 | 16 | 17. The downsample also
// writes the disocclusion mask, from its own pixel's values; 3 and 6 read the application's G-buffer as
// the downsample stores it, so that they need not wait for it. The relight pass, latency-bound on at most
// 2048 groups, shares its interval with two passes that need only earlier levels. 8b reads the world
// cache at the probes, and the emission into it waits until the interpolation has read it.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>

#include "bricklight/vct.h"
#include "gi_context_impl.h"

namespace bricklight::gi::detail {

namespace {

using rhi::Access;

uint32_t groups(uint32_t n, uint32_t size) { return (n + size - 1) / size; }
// Passes over the brick pool fold into a second dimension past this many groups (the shaders index
// y * 65535 * 64 + x).
constexpr uint32_t kMaxGroups = 65535;

}  // namespace

void GiContextImpl::addTrace(rhi::Bindings& b) const { scene_.traceBindings(b); }

void GiContextImpl::addAlphaCache(rhi::Bindings& b, rhi::Access access) const { storageBuffer(b, 7, alphaCache_, access); }

void GiContextImpl::addEnvironment(rhi::Bindings& b, const DispatchDesc& d) const {
    // Both samplers are always bound (gi_environment.glsl); the unused one gets a black 1×1.
    texture(b, 13, d.environmentKind == EnvironmentKind::Cube ? d.environmentMap : blackCube_, environment_);
    texture(b, 14, d.environmentKind == EnvironmentKind::Equirectangular ? d.environmentMap : black2D_, environment_);
}

void GiContextImpl::prepare(const char* label, rhi::ShaderHandle shader, rhi::DispatchState& s) {
    s.shader = shader;
    s.label = label;
    s.bindings.constants.push(rhi::constants(0, camera_));
    s.bindings.constants.push(rhi::constants(1, frame_));
}

void GiContextImpl::run(const char* label, rhi::ShaderHandle shader, rhi::DispatchState& s, uint32_t x, uint32_t y, uint32_t z) {
    prepare(label, shader, s);
    device_.beginMarker(label);
    device_.dispatch(s, x, y, z);
    device_.endMarker();
}

void GiContextImpl::runIndirect(const char* label, rhi::ShaderHandle shader, rhi::DispatchState& s, rhi::BufferHandle args) {
    prepare(label, shader, s);
    device_.beginMarker(label);
    device_.dispatchIndirect(s, args, 0);
    device_.endMarker();
}

void GiContextImpl::runOverProbes(const char* label, rhi::ShaderHandle shader, rhi::BufferHandle probeInfo, rhi::BufferHandle input,
                                  rhi::BufferHandle output, rhi::Access outputAccess) {
    rhi::DispatchState s;
    readBuffer(s.bindings, 0, probeInfo);
    readBuffer(s.bindings, 1, input);
    storageBuffer(s.bindings, 0, output, outputAccess);
    addTrace(s.bindings);
    run(label, shader, s, groups(tilesX_ * tilesY_, 64), 1);
}

void GiContextImpl::fillConstants(const DispatchDesc& d) {
    // Inverted in double: with a near plane far below the far plane (standard depth) a float inverse
    // loses most of the depth range's precision, and positions rebuilt from depth land metres off.
    const glm::dmat4 viewProjection = glm::dmat4(d.camera.projection) * glm::dmat4(d.camera.view);
    const glm::dmat4 previousViewProjection = glm::dmat4(d.camera.previousProjection) * glm::dmat4(d.camera.previousView);
    camera_.viewProjection = glm::mat4(viewProjection);
    camera_.inverseViewProjection = glm::mat4(glm::inverse(viewProjection));
    camera_.previousViewProjection = glm::mat4(previousViewProjection);
    camera_.previousInverseViewProjection = glm::mat4(glm::inverse(previousViewProjection));
    const uint32_t cascades = scene_.desc().cascadeCount;
    const uint32_t start = d.trace.startCascade, end = std::min(d.trace.endCascade, cascades - 1);
    uint32_t flags = 0;
    if (desc_.flags & ContextFlags::ReversedDepth) flags |= FlagReversedDepth;
    if (d.resetHistory) flags |= FlagResetHistory;
    if (historyValid_) flags |= FlagHistoryValid;
    if (!d.gbuffer.motionVectors) flags |= FlagCameraMotion;
    if (!(desc_.flags & ContextFlags::NoProbeParallax)) flags |= FlagProbeParallax;
    frame_ = GpuFrame{};
    frame_.size[0] = width_;
    frame_.size[1] = height_;
    frame_.size[2] = desc_.displayWidth;
    frame_.size[3] = desc_.displayHeight;
    frame_.tiles[0] = tilesX_;
    frame_.tiles[1] = tilesY_;
    frame_.tiles[2] = uint32_t(frameIndex_);
    frame_.tiles[3] = flags;
    frame_.camera = glm::vec4(d.cameraPosition, scene_.cascadeVoxelSize(start));
    frame_.normalScale = glm::vec4(d.gbuffer.normalsUnpackScale, d.roughnessThreshold);
    frame_.normalOffset = glm::vec4(d.gbuffer.normalsUnpackOffset, d.environmentIntensity);
    frame_.inputs[0] = d.gbuffer.roughnessChannel;
    frame_.inputs[1] = d.gbuffer.roughnessPerceptual ? 1u : 0u;
    frame_.inputs[2] = uint32_t(d.environmentKind);
    frame_.inputs[3] = kMaxDiffuseHistory;
    frame_.motion = glm::vec4(d.gbuffer.motionVectorScale, 0.0f, 0.0f);
    frame_.trace = glm::vec4(d.trace.rayPushOff, d.trace.specularRayPushOff, d.trace.tMin, d.trace.tMax);
    frame_.cascades[0] = start;
    frame_.cascades[1] = end;
    frame_.cascades[2] = scene_.desc().atlasBricksPerAxis;
    frame_.cascades[3] = scene_.brickCapacity();
    frame_.epsilon = glm::vec4(d.trace.epsilonScale, d.trace.specularEpsilonScale, 0.0f, 0.0f);
    frame_.traceLimits = glm::vec4(float(d.trace.maxIterationsPerCascade), d.trace.coarsenAfterVoxels, 0.0f, 0.0f);
    frame_.relight[0] = d.lightCount;
    frame_.relight[1] = (d.diffuseAlbedo ? uint32_t(RelightAlbedo) : 0u) | (d.emission ? uint32_t(RelightEmission) : 0u) |
                        (d.emission && !d.previousLitIncludesEmission && !d.emittersInLights ? uint32_t(RelightEmissionInRays) : 0u) |
                        (d.emittersInLights ? uint32_t(RelightEmittersInLights) : 0u) |
                        (d.previousLitIncludesEmission ? uint32_t(RelightLitHoldsEmission) : 0u) |
                        (d.relightBounces ? 0u : uint32_t(RelightDirectOnly)) |
                        (d.lightUnseenSurfaces ? uint32_t(RelightUnseenHits) : 0u) |
                        (d.environmentInDirectLight ? uint32_t(RelightEnvironmentInDirect) : 0u);
    frame_.probes[0] = probeTile_;
    frame_.cache[0] = cacheSlots_ / 4;  // inject_radiance.comp: the last quarter goes to bricks that receive light
    writeChangedRegions();
}

// frame_.cache[1] and changed_ from the field's latest changes.
void GiContextImpl::writeChangedRegions() {
    struct Box {
        glm::vec3 min, max;
        float age = 0.0f;  // frames since the change; a merged box takes the younger
        float volume() const {
            const glm::vec3 s = glm::max(max - min, glm::vec3(0.0f));
            return s.x * s.y * s.z;
        }
    };
    // A change stays a region for kChangeFrames frames: the screen's feedback (last frame's image injected into
    // the cache, the history) carries the light of before the change for that long.
    const uint64_t update = scene_.updateCount();
    // Before the first frame there is no light to refresh (the first update adds everything).
    if (update != changesSeenAt_ && frameIndex_ == 0) changesSeenAt_ = update;
    if (update != changesSeenAt_) {
        changesSeenAt_ = update;
        const float voxel = frame_.camera.w;
        for (const sdf::SdfScene::ChangedBox& c : scene_.latestChanges()) {
            const glm::vec3 size = c.max - c.min;
            const float reach = std::max(kChangeReachVoxels * voxel, std::max(size.x, std::max(size.y, size.z)));
            recentChanges_.push_back({c.min - reach, c.max + reach, frameIndex_});
        }
    }
    std::erase_if(recentChanges_, [&](const RecentChange& c) { return frameIndex_ >= c.frame + kChangeFrames; });
    std::vector<Box> boxes;
    for (const RecentChange& c : recentChanges_) boxes.push_back({c.min, c.max, float(frameIndex_ - c.frame)});
    while (boxes.size() > kMaxChangedRegions) {
        size_t bi = 0, bj = 1;
        float best = INFINITY;
        for (size_t i = 0; i < boxes.size(); ++i)
            for (size_t j = i + 1; j < boxes.size(); ++j) {
                const Box u{glm::min(boxes[i].min, boxes[j].min), glm::max(boxes[i].max, boxes[j].max), 0.0f};
                const float added = u.volume() - boxes[i].volume() - boxes[j].volume();
                if (added < best) best = added, bi = i, bj = j;
            }
        boxes[bi] = {glm::min(boxes[bi].min, boxes[bj].min), glm::max(boxes[bi].max, boxes[bj].max), std::min(boxes[bi].age, boxes[bj].age)};
        boxes.erase(boxes.begin() + long(bj));
    }
    frame_.cache[1] = uint32_t(boxes.size());
    changed_ = {};
    for (size_t i = 0; i < boxes.size(); ++i) {
        changed_.boxes[2 * i] = glm::vec4(boxes[i].min, boxes[i].age);
        changed_.boxes[2 * i + 1] = glm::vec4(boxes[i].max, 0.0f);
    }
}

void GiContextImpl::uploadLights(const DispatchDesc& d) {
    if (d.lightCount == 0) return;
    std::vector<GpuLight> lights(d.lightCount);
    for (uint32_t i = 0; i < d.lightCount; ++i) {
        const Light& l = d.lights[i];
        const bool spot = l.type == LightType::Spot;
        lights[i].position = glm::vec4(l.position, float(uint32_t(l.type)));
        lights[i].color = glm::vec4(l.color, spot ? std::cos(l.spotOuterAngle) : -2.0f);
        if (l.type == LightType::Rect || l.type == LightType::Triangle) {
            const float parallelogram = glm::length(glm::cross(l.edge0, l.edge1));
            lights[i].direction = glm::vec4(l.edge0, l.twoSided ? 1.0f : 0.0f);
            lights[i].edge1 = glm::vec4(l.edge1, l.type == LightType::Rect ? parallelogram : 0.5f * parallelogram);
        } else {
            const glm::vec3 direction = l.type == LightType::Point ? glm::vec3(0.0f, -1.0f, 0.0f) : glm::normalize(l.direction);
            lights[i].direction = glm::vec4(direction, spot ? std::cos(l.spotInnerAngle) : -2.0f);
            lights[i].edge1 = glm::vec4(0.0f);
        }
    }
    // Uploaded only when they change: an upload waits for the last frame's readers of the buffer, and
    // the frame's passes for the upload.
    const size_t bytes = lights.size() * sizeof(GpuLight);
    if (lights.size() == uploadedLights_.size() && std::memcmp(lights.data(), uploadedLights_.data(), bytes) == 0) return;
    device_.writeBuffer(lights_, 0, lights.data(), bytes);
    uploadedLights_ = std::move(lights);
}

bool GiContextImpl::dispatch(const DispatchDesc& d) {
    if (!sceneAlive() || !checkInputs(d)) return false;
    checkScene();
    fillConstants(d);
    uploadLights(d);
    const int cur = int(frameIndex_ & 1u), prev = cur ^ 1;
    const bool specular = !(desc_.flags & ContextFlags::NoSpecular);
    const bool denoise = !(desc_.flags & ContextFlags::NoDenoiser);
    const uint32_t capacity = scene_.brickCapacity();
    const rhi::BufferHandle owners = scene_.brickOwnerBuffer();
    device_.beginMarker(desc_.debugName.c_str());

    const bool relight = bool(d.diffuseAlbedo);
    // Passes 3 and 6 read the application's G-buffer as pass 1 stores it (gi_input.glsl), so that the three
    // run side by side.
    auto addInputs = [&](rhi::Bindings& b) {
        texture(b, 0, d.gbuffer.depth, point_);
        texture(b, 1, d.gbuffer.normals, point_);
        texture(b, 2, d.gbuffer.roughness, point_);
    };
    {  // 1, 2. downsample; disocclusion mask
        rhi::DispatchState s;
        addInputs(s.bindings);
        // Without motion vectors: a 1x1 black stand-in whose texel the shader fetches and ignores (it selects the
        // camera's motion instead of branching on the flag: lavapipe recompiles per dispatch on such branches).
        texture(s.bindings, 3, d.gbuffer.motionVectors ? d.gbuffer.motionVectors : black2D_, point_);
        texture(s.bindings, 4, depth_[prev], point_);
        texture(s.bindings, 5, surface_[prev], point_);
        image(s.bindings, 0, depth_[cur], Access::Write);
        image(s.bindings, 1, surface_[cur], Access::Write);
        image(s.bindings, 2, motion_, Access::Write);
        image(s.bindings, 3, disocclusion_, Access::Write);
        run("downsample", shaders_.downsample, s, groups(width_, 8), groups(height_, 8));
    }
    {  // 3. clear the cache entries of freed bricks; pick the bricks to re-light
        rhi::DispatchState s;
        readBuffer(s.bindings, 0, owners);
        storageBuffer(s.bindings, 0, cacheOwners_, Access::ReadWrite);
        storageBuffer(s.bindings, 1, brickSH_, Access::Write);
        storageBuffer(s.bindings, 2, brickMaterial_, Access::ReadWrite);
        storageBuffer(s.bindings, 3, relightList_[cur], Access::ReadWrite);
        storageBuffer(s.bindings, 6, relightList_[prev], Access::Write);  // emptied for the next frame
        storageBuffer(s.bindings, 4, slotOfBrick_, Access::ReadWrite);
        storageBuffer(s.bindings, 5, freeSlots_, Access::ReadWrite);
        image(s.bindings, 0, radianceCache_, Access::Write);
        addInputs(s.bindings);
        addTrace(s.bindings);
        addAlphaCache(s.bindings, Access::ReadWrite);  // forgets the alpha cells of reallocated bricks
        s.bindings.constants.push(rhi::constants(3, changed_));
        run("clear freed bricks", shaders_.clearFreed, s, std::min(groups(capacity, 64), kMaxGroups), groups(groups(capacity, 64), kMaxGroups));
        // The pass's cells are old now (only a frame with an alpha pass set the word: alphaPassState).
        if ((desc_.flags & ContextFlags::AlphaCache) && alphaPassClearedAt_ == frameIndex_ + 1) device_.clearBuffer(alphaCache_, {4, 4}, 0);
    }
    {  // 6. spawn screen probes
        rhi::DispatchState s;
        addInputs(s.bindings);
        storageBuffer(s.bindings, 0, probeInfo_[cur], Access::Write);
        run("spawn probes", shaders_.spawn, s, groups(tilesX_, 8), groups(tilesY_, 8));
    }
    {  // 4. inject last frame's lit image into the radiance cache
        const uint32_t tile = injectTile_;
        rhi::DispatchState s;
        struct {
            uint32_t inject[4];
        } pass{{tile, 0, 0, 0}};
        s.bindings.constants.push(rhi::constants(2, pass));
        texture(s.bindings, 0, depth_[cur], point_);
        texture(s.bindings, 1, surface_[cur], point_);
        texture(s.bindings, 2, motion_, point_);
        texture(s.bindings, 3, disocclusion_, point_);
        texture(s.bindings, 4, d.previousLitOutput, linear_);
        texture(s.bindings, 5, relight ? d.diffuseAlbedo : black2D_, linear_);
        texture(s.bindings, 6, d.emission ? d.emission : black2D_, linear_);
        image(s.bindings, 0, radianceCache_, Access::ReadWrite);
        storageBuffer(s.bindings, 0, brickMaterial_, Access::ReadWrite);
        storageBuffer(s.bindings, 1, slotOfBrick_, Access::ReadWrite);
        storageBuffer(s.bindings, 2, freeSlots_, Access::ReadWrite);
        addTrace(s.bindings);
        s.bindings.constants.push(rhi::constants(3, changed_));
        run("inject radiance", shaders_.inject, s, groups(groups(width_, tile), 8), groups(groups(height_, tile), 8));
    }
    {  // 7. reproject screen probes
        rhi::DispatchState s;
        readBuffer(s.bindings, 0, probeInfo_[prev]);
        storageBuffer(s.bindings, 0, probeInfo_[cur], Access::ReadWrite);
        texture(s.bindings, 0, probes_[prev], point_);
        texture(s.bindings, 1, motion_, point_);
        image(s.bindings, 0, probes_[cur], Access::Write);
        run("reproject probes", shaders_.reprojectProbes, s, tilesX_, tilesY_);
    }
    {  // 10. reproject GI history
        rhi::DispatchState s;
        texture(s.bindings, 0, motion_, point_);
        texture(s.bindings, 1, disocclusion_, point_);
        texture(s.bindings, 2, diffuseHistory_[prev], linear_);
        texture(s.bindings, 3, specularHistory_[prev], linear_);
        image(s.bindings, 0, diffuseHistory_[cur], Access::Write);
        image(s.bindings, 1, specularHistory_[cur], Access::Write);
        run("reproject GI", shaders_.reprojectGi, s, groups(width_, 8), groups(height_, 8));
    }
    if (relight) {  // 4b. re-light the cache texels of bricks the camera has not seen lately
        rhi::DispatchState s;
        readBuffer(s.bindings, 0, relightList_[cur]);
        readBuffer(s.bindings, 1, owners);
        readBuffer(s.bindings, 2, brickMaterial_);
        readBuffer(s.bindings, 3, lights_);
        storageBuffer(s.bindings, 0, slotOfBrick_, Access::Read);
        image(s.bindings, 0, radianceCache_, Access::ReadWrite);
        addTrace(s.bindings);
        addAlphaCache(s.bindings);
        addEnvironment(s.bindings, d);
        runIndirect("relight cache", shaders_.relight, s, relightList_[cur]);
    }
    {  // 5. propagate brick SH in one cascade (the finest every other frame, the next every fourth, ...)
        const uint32_t start = frame_.cascades[0], end = frame_.cascades[1];
        const uint32_t cascade = std::min(end, start + uint32_t(std::countr_zero(frameIndex_ + 1)));
        rhi::DispatchState s;
        struct {
            uint32_t cascade[4];
        } pass{{cascade, 0, 0, 0}};
        s.bindings.constants.push(rhi::constants(2, pass));
        readBuffer(s.bindings, 0, owners);
        storageBuffer(s.bindings, 0, brickSH_, Access::ReadWrite);
        addTrace(s.bindings);
        run("propagate SH", shaders_.propagate, s, std::min(groups(capacity, 64), kMaxGroups), groups(groups(capacity, 64), kMaxGroups));
    }
    if (specular) {  // 9. specular pre-trace (one ray per 4×4 tile)
        rhi::DispatchState s;
        texture(s.bindings, 0, depth_[cur], point_);
        texture(s.bindings, 1, surface_[cur], point_);
        image(s.bindings, 0, pretrace_, Access::Write);
        addTrace(s.bindings);
        addAlphaCache(s.bindings);
        run("specular pretrace", shaders_.pretrace, s, groups(groups(width_, kPretraceTile), 8), groups(groups(height_, kPretraceTile), 8));
    }
    {  // 8. fill screen probes by tracing the field
        rhi::DispatchState s;
        readBuffer(s.bindings, 0, probeInfo_[cur]);
        image(s.bindings, 0, probes_[cur], Access::ReadWrite);
        image(s.bindings, 1, radianceCache_, Access::Read);
        readBuffer(s.bindings, 2, lights_);
        readBuffer(s.bindings, 3, slotOfBrick_);
        storageBuffer(s.bindings, 0, probeIrradianceSH_, Access::Read);  // last frame's, for unseen hits
        addTrace(s.bindings);
        addAlphaCache(s.bindings);
        addEnvironment(s.bindings, d);
        if (d.unseenLight) d.unseenLight->traceBindings(s.bindings, 0, 1);  // fill_probes_body.glsl's slots
        const uint32_t fillGroups = groups(tilesX_ * tilesY_, 4);  // 4 probes per group
        run("fill probes", d.unseenLight ? shaders_.fillVct : shaders_.fill, s, std::min(fillGroups, kMaxGroups), groups(fillGroups, kMaxGroups));
    }
    // 8b. the world cache at each probe (for the projection's blend)
    runOverProbes("probe world cache", shaders_.probeWorld, probeInfo_[cur], brickSH_, probeWorldSH_, Access::Write);
    if (specular) {  // 11. specular trace (full internal resolution, inside the pre-traced brick)
        rhi::DispatchState s;
        texture(s.bindings, 0, depth_[cur], point_);
        texture(s.bindings, 1, surface_[cur], point_);
        texture(s.bindings, 2, pretrace_, point_);
        readBuffer(s.bindings, 0, owners);
        image(s.bindings, 0, specularTraced_, Access::Write);
        image(s.bindings, 1, radianceCache_, Access::Read);
        readBuffer(s.bindings, 3, slotOfBrick_);
        addTrace(s.bindings);
        addAlphaCache(s.bindings);
        addEnvironment(s.bindings, d);
        run("specular trace", shaders_.specularTrace, s, groups(width_, 8), groups(height_, 8));
    }
    {  // 12. project probes to SH
        rhi::DispatchState s;
        readBuffer(s.bindings, 0, probeInfo_[cur]);
        texture(s.bindings, 0, probes_[cur], point_);
        storageBuffer(s.bindings, 0, probeSH_, Access::Write);
        storageBuffer(s.bindings, 1, probeIrradianceSH_, Access::Write);
        readBuffer(s.bindings, 2, probeWorldSH_);
        image(s.bindings, 0, radianceCache_, Access::Read);
        readBuffer(s.bindings, 3, slotOfBrick_);
        addTrace(s.bindings);
        const uint32_t projectGroups = groups(tilesX_ * tilesY_, 4);  // 4 probes per group
        run("project probes", shaders_.project, s, std::min(projectGroups, kMaxGroups), groups(projectGroups, kMaxGroups));
    }
    {  // 14. interpolate and accumulate
        rhi::DispatchState s;
        texture(s.bindings, 0, depth_[cur], point_);
        texture(s.bindings, 1, surface_[cur], point_);
        texture(s.bindings, 2, specularTraced_, point_);
        readBuffer(s.bindings, 0, probeInfo_[cur]);
        readBuffer(s.bindings, 1, probeIrradianceSH_);
        readBuffer(s.bindings, 2, brickSH_);
        image(s.bindings, 0, diffuseHistory_[cur], Access::ReadWrite);
        image(s.bindings, 1, specularHistory_[cur], Access::ReadWrite);
        addTrace(s.bindings);
        s.bindings.constants.push(rhi::constants(3, changed_));
        run("interpolate", shaders_.interpolate, s, groups(width_, 8), groups(height_, 8));
    }
    // 13. emit the probes into the brick SH irradiance cache (after the interpolation, the last pass of the
    // frame to read it, so that the two do not wait for each other)
    runOverProbes("emit irradiance", shaders_.emit, probeInfo_[cur], probeSH_, brickSH_, Access::ReadWrite);
    rhi::TextureHandle finalDiffuse = diffuseHistory_[cur], finalSpecular = specularHistory_[cur];
    if (denoise) {  // 15, 16. bilateral blur, x (into last frame's history, free since pass 10) then y
        struct Step {
            const char* label;
            int32_t direction[4];
            rhi::TextureHandle in[2], out[2];
        };
        const Step steps[2] = {
            {"blur x", {1, 0, 0, 0}, {diffuseHistory_[cur], specularHistory_[cur]}, {diffuseHistory_[prev], specularHistory_[prev]}},
            {"blur y", {0, 1, 0, 0}, {diffuseHistory_[prev], specularHistory_[prev]}, {resolvedDiffuse_, resolvedSpecular_}},
        };
        for (const Step& step : steps) {
            struct {
                int32_t direction[4];
            } pass{{step.direction[0], step.direction[1], 0, 0}};
            rhi::DispatchState s;
            s.bindings.constants.push(rhi::constants(2, pass));
            texture(s.bindings, 0, step.in[0], point_);
            texture(s.bindings, 1, step.in[1], point_);
            texture(s.bindings, 2, depth_[cur], point_);
            texture(s.bindings, 3, surface_[cur], point_);
            image(s.bindings, 0, step.out[0], Access::Write);
            image(s.bindings, 1, step.out[1], Access::Write);
            run(step.label, shaders_.blur, s, groups(width_, 8), groups(height_, 8));
        }
        finalDiffuse = resolvedDiffuse_;
        finalSpecular = resolvedSpecular_;
    }
    {  // 17. upsample to the display outputs
        rhi::DispatchState s;
        struct {
            uint32_t options[4];
        } pass{{d.outputSpecular ? 1u : 0u, 0, 0, 0}};
        s.bindings.constants.push(rhi::constants(2, pass));
        texture(s.bindings, 0, finalDiffuse, point_);
        texture(s.bindings, 1, finalSpecular, point_);
        texture(s.bindings, 2, depth_[cur], point_);
        texture(s.bindings, 3, surface_[cur], point_);
        texture(s.bindings, 4, d.gbuffer.depth, point_);
        texture(s.bindings, 5, d.gbuffer.normals, point_);
        image(s.bindings, 0, d.outputDiffuse, Access::Write);
        image(s.bindings, 1, d.outputSpecular ? d.outputSpecular : dummyStorage_, Access::Write);
        run("upsample", shaders_.upsample, s, groups(desc_.displayWidth, 8), groups(desc_.displayHeight, 8));
    }
    recordCameraCheck(d);
    device_.endMarker();
    lastInputs_.depth = d.gbuffer.depth;
    lastInputs_.normals = d.gbuffer.normals;
    lastInputs_.roughness = d.gbuffer.roughness;
    lastInputs_.environment.environmentKind = d.environmentKind;
    lastInputs_.environment.environmentMap = d.environmentMap;
    lastFrame_ = cur;
    ++frameIndex_;
    historyValid_ = true;
    return true;
}

}  // namespace bricklight::gi::detail
