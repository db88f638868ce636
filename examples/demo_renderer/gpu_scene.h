// A SceneGeometry on the GPU for the renderer's passes: world triangles in BVH order, the BVH, materials,
// emitters (examples/demo_renderer/shaders/scene_trace.glsl traces them), and a vertex buffer for rasterization.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "bricklight/rhi.h"
#include "scene_geometry.h"

namespace bricklight::render {

// BL_CONSTANTS(1) of every pass that includes scene_trace.glsl.
struct SceneLightConstants {
    glm::vec4 sky;            // rgb radiance
    glm::vec4 sunDirection;   // xyz towards the sun
    glm::vec4 sunIrradiance;  // rgb
    uint32_t counts[4];       // x emitters, y seed, z max bounces
    glm::vec4 lightWeight;    // x total emitter weight, y ray offset (self-intersection)
};

// What both renderers check before they start: the image size and the camera. False with `error` set.
bool checkImageSize(uint32_t width, uint32_t height, std::string* error);
// A storage buffer of `bytes` that a pass binds whole: refused before any work when it exceeds the device's
// maxStorageBufferRange (the device would reject the binding and the image would come out black).
bool checkStorageRange(const rhi::IDevice& device, uint64_t bytes, const std::string& what, std::string* error);
bool checkCamera(const scenes::Camera& camera, std::string* error);

class GpuScene {
public:
    // Null with `error` set for an empty scene, non-finite positions, indices out of range, negative
    // albedo/emission, transmission outside [0, 1], an ior outside (1, 3], a BVH deeper than the traversal stack.
    // `previous` (optional): the same scene's world positions one frame earlier (an animated scene), for
    // motion vectors; used when it has as many vertices.
    static std::unique_ptr<GpuScene> create(rhi::IDevice& device, const scenes::SceneGeometry& scene, std::string* error,
                                            const std::vector<glm::vec3>* previous = nullptr);
    ~GpuScene();
    // Read buffers 0..6 (triangles, BVH, materials, emitters, point lights, texture coordinates, normals),
    // the base-colour texture array (texture slot 4) and the loop-budget counter (storage buffer 4) as
    // scene_trace.glsl declares them: every pass that traces rays reads the textures, for the alpha test of
    // alpha-tested materials.
    void bind(rhi::Bindings& bindings) const;
    // The former form (`textures` chose whether slot 4 was bound); the textures are always bound now. Kept
    // for callers outside the renderer's own files until they drop the argument.
    void bind(rhi::Bindings& bindings, bool /*textures*/) const { bind(bindings); }
    // Shader invocations (pixels, fragments) of every pass so far whose rays a CPU driver's limit on loop
    // iterations cut short (scene_trace.glsl's loopBudgetSpent): their results are wrong. Zero on GPUs. A
    // blocking read-back.
    uint64_t invocationsCutShort() const;
    // Takes over the counter of the scene this one replaces (an animated scene's previous state), so the count
    // runs on over frames without a read-back.
    void continueCountOf(GpuScene& replaced) { std::swap(loopBudget_, replaced.loopBudget_); }
    rhi::TextureHandle textureArray() const { return textures_; }
    rhi::SamplerHandle textureSampler() const { return sampler_; }
    static constexpr uint32_t kTextureSize = 256;  // every base-colour texture is resampled to this square
    SceneLightConstants lightConstants(uint32_t seed, uint32_t maxBounces) const;
    uint32_t triangleCount() const { return triangles_; }
    // The vertex buffer holds the opaque triangles first, then the glass ones (transmission > 0).
    uint32_t opaqueTriangleCount() const { return opaqueTriangles_; }
    bool hasAlphaTested() const { return alphaTested_; }  // a mesh with an alpha cut-off > 0
    uint32_t glassTriangleCount() const { return triangles_ - opaqueTriangles_; }
    // 3 vertices per triangle, in the scene's order, glass last (layout: kVertexStride).
    rhi::BufferHandle vertexBuffer() const { return vertices_; }
    rhi::BufferHandle materialBuffer() const { return materials_; }
    // position, shading normal, material, previous position, uv, geometric normal
    static constexpr uint32_t kVertexStride = 60;
    // The vertex buffer and all six attributes at locations 0..5, as render/gbuffer.vert reads them.
    void bindVertices(rhi::DrawCallState& state) const;
    // What the GI's alpha pass with render/alpha_pass.vert and .frag reads (position, material and texture
    // coordinates; the materials at read buffer 2, the textures at slot 4), and its draw's arguments.
    void bindAlphaPass(rhi::DrawCallState& state, rhi::DrawArgs* args) const;
    const std::vector<glm::vec3>& worldPositions() const { return positions_; }
    float rayOffset() const { return epsilon_; }

private:
    explicit GpuScene(rhi::IDevice& device) : device_(device) {}
    rhi::IDevice& device_;
    rhi::BufferHandle triangleBuffer_, nodes_, materials_, lights_, pointLights_, vertices_, uvs_, normals_, loopBudget_;
    rhi::TextureHandle textures_;
    rhi::SamplerHandle sampler_;
    uint32_t pointLightCount_ = 0;
    scenes::Environment environment_;
    std::vector<glm::vec3> positions_;
    uint32_t lightCount_ = 0, triangles_ = 0, opaqueTriangles_ = 0;
    bool alphaTested_ = false;
    float lightWeight_ = 0.0f, epsilon_ = 1e-4f;
};

}  // namespace bricklight::render
