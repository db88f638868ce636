// C++ mirror of the GI passes' constant blocks (shaders/gi/gi_common.glsl): std140, vec4-aligned.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace bricklight::gi::detail {

struct GpuCamera {  // BL_CONSTANTS(0)
    glm::mat4 viewProjection;
    glm::mat4 inverseViewProjection;
    glm::mat4 previousViewProjection;
    glm::mat4 previousInverseViewProjection;
};
static_assert(sizeof(GpuCamera) == 256);

enum GpuFlags : uint32_t {
    FlagReversedDepth = 1u,
    FlagResetHistory = 2u,
    FlagHistoryValid = 8u,
};

struct GpuFrame {  // BL_CONSTANTS(1)
    uint32_t size[4];       // internal w, h, display w, h
    uint32_t tiles[4];      // probe tiles x, y, frame index, flags
    glm::vec4 camera;       // position, finest traced voxel size
    glm::vec4 normalScale;  // xyz, w roughness threshold
    glm::vec4 normalOffset; // xyz, w environment intensity
    uint32_t inputs[4];     // roughness channel, roughness perceptual, environment kind, max history
    glm::vec4 motion;       // xy scale
    glm::vec4 trace;        // push-off, specular push-off, tMin, tMax
    uint32_t cascades[4];   // start, end, atlas bricks per axis, brick capacity
    glm::vec4 epsilon;      // diffuse, specular epsilon scale
};
static_assert(sizeof(GpuFrame) == 160);

constexpr uint32_t kProbeTile = 8;          // internal pixels per probe tile side (8×8 texels per probe)
constexpr uint32_t kInjectTile = 2;         // one injected pixel per tile per frame (GI_INJECT_TILE)
constexpr uint32_t kPretraceTile = 4;       // one specular pre-trace ray per 4×4 tile
constexpr uint32_t kCacheTexelsPerBrick = 4;  // radiance cache texels per brick side
constexpr uint32_t kShCoefficients = 9;
constexpr uint32_t kMaxDiffuseHistory = 16;

}  // namespace bricklight::gi::detail
