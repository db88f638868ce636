// The renderer's fast path: a G-buffer rasterized through DrawCallState records (albedo + roughness,
// normal, emission + metalness, motion vectors, depth), then direct lighting from emitters, the sun and the
// sky with ray-traced shadows (shaders/render/direct_light.comp, the path tracer's estimator).
#pragma once

#include <memory>
#include <string>

#include "gpu_scene.h"
#include "path_tracer.h"

namespace bricklight::render {

struct RasterOptions {
    uint32_t width = 256, height = 256;
    uint32_t lightSamples = 16;  // emitter (and sky) samples per pixel for direct lighting
    uint32_t seed = 1;
};

class RasterRenderer {
public:
    static std::unique_ptr<RasterRenderer> create(rhi::IDevice& device, const scenes::SceneGeometry& scene,
                                                  const RasterOptions& options, std::string* error);
    ~RasterRenderer();
    // The next frame's camera; the previous one gives the motion vectors.
    bool setCamera(const scenes::Camera& camera, std::string* error);
    // The scene of the next frame (an animated scene's next state): its vertices' previous positions are
    // this frame's, for motion vectors. Fails, changing nothing, on a bad scene.
    bool setScene(const scenes::SceneGeometry& scene, std::string* error);
    void render();  // records the G-buffer draw and the lighting dispatch
    // Combined (= direct until GI lands), direct, albedo, normal, depth; indirect-diffuse is zero.
    Image read(Aov aov);
    Image readMotion();  // rg = UV motion (current - previous), b = 0
    uint32_t triangleCount() const { return scene_->triangleCount(); }

private:
    explicit RasterRenderer(rhi::IDevice& device) : device_(device) {}
    rhi::IDevice& device_;
    RasterOptions options_;
    std::unique_ptr<GpuScene> scene_;
    rhi::ShaderHandle vertex_, fragment_, lighting_;
    rhi::TextureHandle albedo_, normal_, emission_, motion_, position_, depth_;
    rhi::SamplerHandle point_;
    rhi::BufferHandle direct_;
    scenes::Camera camera_;
    glm::mat4 viewProjection_{1.0f}, previousViewProjection_{1.0f};
    uint32_t frame_ = 0;
};

// The renderer's camera matrix: right-handed view, depth [0, 1], clip-space y down (row 0 at the top).
glm::mat4 viewProjection(const scenes::Camera& camera, float aspect, float sceneSize);

}  // namespace bricklight::render
