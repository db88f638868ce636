// The GiContext implementation, split by concept:
//   gi_context.cpp    creation, resources, capability checks, memory, reset, cache read-back
//   gi_inputs.cpp     checks of a frame's inputs (names the input and the problem)
//   gi_dispatch.cpp   the frame's passes as records
//   gi_debug_view.cpp the debug views
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "../common/diagnostic_log.h"
#include "bricklight/gi.h"
#include "gi_constants.h"

namespace bricklight::gi::detail {

// Binding helpers for the passes' records: whole textures, mip 0 of storage images, whole buffers.
inline void texture(rhi::Bindings& b, uint8_t slot, rhi::TextureHandle t, rhi::SamplerHandle s) {
    b.textures.push({slot, rhi::wholeTexture(t), s});
}
inline void image(rhi::Bindings& b, uint8_t slot, rhi::TextureHandle t, rhi::Access access) {
    rhi::StorageImageBinding i;
    i.slot = slot;
    i.view = rhi::textureMip(t, 0);
    i.access = access;
    b.storageImages.push(i);
}
inline void readBuffer(rhi::Bindings& b, uint8_t slot, rhi::BufferHandle buffer) { b.readBuffers.push({slot, buffer, {}}); }
inline void storageBuffer(rhi::Bindings& b, uint8_t slot, rhi::BufferHandle buffer, rhi::Access access) {
    b.storageBuffers.push({slot, buffer, {}, access});
}

class GiContextImpl final : public GiContext {
public:
    GiContextImpl(rhi::IDevice& device, const sdf::SdfScene& scene, const ContextDesc& desc)
        : device_(device), scene_(scene), sceneToken_(scene.lifetimeToken()), desc_(desc), log_(desc.debugName + ": ") {}
    ~GiContextImpl() override;
    bool init(Error* error);

    bool dispatch(const DispatchDesc& desc) override;
    bool debugView(const DebugViewDesc& desc) override;
    void reset() override;
    MemoryUse memoryUse() const override;
    const ContextDesc& desc() const override { return desc_; }
    uint32_t internalWidth() const override { return width_; }
    uint32_t internalHeight() const override { return height_; }
    uint32_t probeTile() const override { return probeTile_; }
    const Error& lastError() const override { return log_.lastError(); }
    std::vector<Diagnostic> diagnostics() const override { return log_.diagnostics(); }
    void readCaches(std::vector<float>* radiance, std::vector<float>* brickSH) override;
    uint32_t radianceCacheBricksInUse() override;
    bool traceReflectionRays(const ReflectionRaysDesc& desc) override;  // gi_reflections.cpp
    // gi_alpha_pass.cpp
    std::optional<rhi::DrawCallState> alphaPassState(rhi::ShaderHandle fragmentShader, Error* error) override;
    std::vector<float> readAlphaCoverage(std::vector<uint32_t>* fragments) override;
    rhi::BufferHandle alphaCacheBuffer() const override { return alphaCache_; }
    uint64_t raysAtAlphaBound() override;

private:
    bool fail(ErrorCode code, const std::string& message);  // reports an error, returns false
    void warnOnce(ErrorCode code, const std::string& message);
    // False (with a DependencyDestroyed error) once the scene is gone: nothing may touch scene_ then.
    bool sceneAlive();
    // gi_inputs.cpp
    bool checkInputs(const DispatchDesc& d);
    bool checkLights(const DispatchDesc& d);
    // gi_dispatch.cpp
    void fillConstants(const DispatchDesc& d);
    void writeChangedRegions();  // gi_dispatch.cpp
    void uploadLights(const DispatchDesc& d);
    void addTrace(rhi::Bindings& b) const;
    // The alpha cache at storage buffer 7 (gi_alpha.glsl), for the passes that trace rays through foliage (atomic:
    // they count the rays that reach their bound on cards passed in its header).
    void addAlphaCache(rhi::Bindings& b, rhi::Access access = rhi::Access::Atomic) const;
    void addEnvironment(rhi::Bindings& b, const DispatchDesc& d) const;
    // Sets the shader, the label and the camera/frame constants, then records the dispatch in a marker.
    void prepare(const char* label, rhi::ShaderHandle shader, rhi::DispatchState& s);
    void run(const char* label, rhi::ShaderHandle shader, rhi::DispatchState& s, uint32_t x, uint32_t y, uint32_t z = 1);
    void runIndirect(const char* label, rhi::ShaderHandle shader, rhi::DispatchState& s, rhi::BufferHandle args);
    // A pass of one thread per probe (64-thread groups) that reads the probe info and one buffer and writes
    // another, with the SDF bound: the world-cache read at the probes (8b) and the emission (13).
    // gi_camera_check.cpp
    void checkScene();
    void recordCameraCheck(const DispatchDesc& d);
    void pollCameraCheck();
    void runOverProbes(const char* label, rhi::ShaderHandle shader, rhi::BufferHandle probeInfo, rhi::BufferHandle input,
                       rhi::BufferHandle output, rhi::Access outputAccess);

    rhi::IDevice& device_;
    const sdf::SdfScene& scene_;
    std::weak_ptr<const void> sceneToken_;  // expires when scene_ is destroyed
    ContextDesc desc_;
    bricklight::detail::DiagnosticLog log_;
    uint32_t width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0;
    uint32_t injectTile_ = 2;  // ContextDesc::injectTile, resolved
    std::vector<GpuLight> uploadedLights_;  // what the lights buffer holds (uploaded again only on change)
    uint32_t probeTile_ = 8;   // ContextDesc::probeTile, resolved
    uint32_t cacheSlots_ = 0;  // radiance cache slots (bricks it can hold)
    uint32_t cacheDepth_ = 0;  // radiance cache image depth (texels); the image is 256 × 256 × cacheDepth_

    struct Shaders {
        rhi::ShaderHandle downsample, clearFreed, inject, propagate, spawn, reprojectProbes, fill, fillVct, pretrace,
            relight, reprojectGi, specularTrace, project, emit, probeWorld, interpolate, blur, upsample, debug, cameraCheck,
            reflectionTrace, alphaPass;
    } shaders_;

    rhi::TextureHandle depth_[2], surface_[2], motion_, disocclusion_, probes_[2], pretrace_, specularTraced_;
    rhi::TextureHandle diffuseHistory_[2], specularHistory_[2], resolvedDiffuse_, resolvedSpecular_;
    rhi::TextureHandle radianceCache_, blackCube_, black2D_, dummyStorage_;
    rhi::BufferHandle probeInfo_[2], probeSH_, probeIrradianceSH_, probeWorldSH_, brickSH_, cacheOwners_, brickMaterial_, relightList_[2], lights_, slotOfBrick_, freeSlots_;
    rhi::SamplerHandle point_, linear_, environment_;
    // The alpha cache (gi_alpha.glsl): a 4-word header ([0] = 1 when kept), then 64 words per brick; 16 bytes
    // (header 0) without ContextFlags::AlphaCache. alphaRaster_ sizes the alpha pass's rasterization.
    rhi::BufferHandle alphaCache_;
    rhi::TextureHandle alphaRaster_;
    uint64_t alphaPassClearedAt_ = 0;  // frameIndex_ + 1 of the dispatch whose alpha pass cleared the counts

    GpuCamera camera_{};
    GpuFrame frame_{};
    GpuChangedRegions changed_{};  // this frame's (writeChangedRegions)
    struct RecentChange {
        glm::vec3 min, max;  // grown by the reach
        uint64_t frame;      // frameIndex_ when seen
    };
    std::vector<RecentChange> recentChanges_;
    uint64_t changesSeenAt_ = 0;  // the field's update whose changes are in recentChanges_
    uint64_t frameIndex_ = 0;
    int lastFrame_ = 0;  // [cur] of the latest dispatch (for the debug views)
    bool historyValid_ = false;
    // The last dispatch()'s G-buffer and environment, which traceReflectionRays() reads.
    struct LastInputs {
        rhi::TextureHandle depth, normals, roughness;
        DispatchDesc environment;  // only its environment fields are set
    } lastInputs_;
    struct {
        uint32_t list[4];
    } reflectionPass_{};  // reflection_trace.comp's constants (recorded by pointer)

    struct CameraCheck {
        rhi::BufferHandle counts;         // 4 uints (camera_check.comp)
        std::deque<uint64_t> pending;     // read-back tickets, oldest first
        uint32_t badInARow = 0;
        bool warned = false;
        float lastOffSurfaceFraction = -1.0f;  // of the latest decidable check; -1: none yet
    } cameraCheck_;
};

}  // namespace bricklight::gi::detail
