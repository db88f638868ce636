// The application's own passes around Bricklight: the G-buffer draw before GI and the composite after it,
// both complete records (rhi::DrawCallState, rhi::DispatchState) with shaders this project compiles itself
// (bricklight_add_shaders in CMakeLists.txt).
#pragma once

#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "bricklight/rhi.h"
#include "bricklight/sdf.h"
#include "scene.h"

namespace integration {

// The frame's images, all display size.
struct FrameImages {
    bricklight::rhi::TextureHandle depth;       // D32_FLOAT, depth [0, 1], 1 = nothing drawn
    bricklight::rhi::TextureHandle normal;      // RGBA16_FLOAT, world normal in xyz
    bricklight::rhi::TextureHandle albedo;      // RGBA8_UNORM, linear albedo + roughness in alpha
    bricklight::rhi::TextureHandle motion;      // RG16_FLOAT, UV-space motion (current - previous)
    bricklight::rhi::TextureHandle giDiffuse;   // RGBA16_FLOAT, written by GI
    bricklight::rhi::TextureHandle giSpecular;  // RGBA16_FLOAT, written by GI
    bricklight::rhi::TextureHandle lit;         // RGBA16_FLOAT, the composite's result, GI's input next frame
    bricklight::rhi::TextureHandle direct;      // RGBA16_FLOAT, direct light alone + sun visibility (checks)
};

class Passes {
public:
    static std::unique_ptr<Passes> create(bricklight::rhi::IDevice& device, uint32_t width, uint32_t height, std::string* error);
    ~Passes();

    const FrameImages& images() const { return images_; }

    bool drawGBuffer(const RoomBuffers& room, const glm::mat4& viewProjection, const glm::mat4& previousViewProjection);
    // Direct sunlight with shadows traced through `field`, plus the GI outputs; writes lit and direct.
    bool composite(const bricklight::sdf::SdfScene& field, const glm::mat4& viewProjection, const glm::vec3& eye, const Sun& sun,
                   float shadowRayOffset);

private:
    explicit Passes(bricklight::rhi::IDevice& device) : device_(device) {}
    bricklight::rhi::IDevice& device_;
    uint32_t width_ = 0, height_ = 0;
    FrameImages images_;
    bricklight::rhi::SamplerHandle point_;
    bricklight::rhi::ShaderHandle gbufferVertex_, gbufferFragment_, composite_;
};

}  // namespace integration
