// Cascaded shadow maps for the sun (CPU side): where the cascades split the view, and each cascade's
// orthographic view-projection, fitted stably. The renderer draws them (raster_renderer_shadows.cpp) and the
// direct lighting reads them (examples/demo_renderer/shaders/shadow_sun.glsl). docs/render.md, "Shadows".
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace bricklight::render {

constexpr uint32_t kShadowCascades = 4;
// Texels of margin kept on every side of a cascade's map around its sphere: PCF kernels up to this radius − 1
// (kMaxShadowPcfRadius) and the normal offset stay inside the map.
constexpr uint32_t kShadowBorderTexels = 4;
constexpr uint32_t kMaxShadowPcfRadius = kShadowBorderTexels - 1;
constexpr uint32_t kMinShadowResolution = 64, kMaxShadowResolution = 4096;

// Where the view is cut: split i of kShadowCascades + 1 is the view distance where cascade i - 1 ends and cascade
// i begins (split 0 = nearPlane, the last = farPlane). The practical scheme: lambda·log + (1 − lambda)·uniform. The
// logarithmic part starts at max(nearPlane, farPlane / 1000), so that a tiny near plane does not squeeze the first
// cascades to nothing.
std::array<float, kShadowCascades + 1> cascadeSplits(float nearPlane, float farPlane, float lambda);

struct ShadowCascade {
    glm::mat4 viewProjection{1.0f};  // world → clip: x, y in [−1, 1] over the map, depth [0, 1] (0 nearest the sun)
    float splitNear = 0.0f, splitFar = 0.0f;  // the view distances (along the camera's forward axis) it covers
    float radius = 0.0f;      // of the bounding sphere of its slice of the frustum
    float texelSize = 0.0f;   // world units per shadow-map texel: 2·radius / (resolution − 2·kShadowBorderTexels − 1)
    glm::vec2 origin{0.0f};   // the map's lower corner in light space (x, y): a whole number of texels
    float depthRange = 0.0f;  // world units from depth 0 to depth 1
};

struct CascadeFitDesc {
    glm::vec3 eye{0.0f}, forward{0.0f, 0.0f, -1.0f};
    float verticalFovDegrees = 60.0f, aspect = 1.0f;
    float nearPlane = 0.01f;
    float shadowDistance = 100.0f;  // the cascades cover the view up to this distance along forward
    float splitLambda = 0.75f;
    uint32_t resolution = 1024;     // texels per side of each cascade's map
    glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};  // towards the sun
    glm::vec3 sceneMin{-1.0f}, sceneMax{1.0f};  // every caster lies inside (the depth range spans it)
};

// The cascades. Stable fitting: each covers the bounding sphere of its slice of the view frustum, whose radius
// depends only on the slice's distances and the field of view (a camera that turns keeps every cascade's size),
// and its light-space origin is snapped to whole texels (a camera that moves shifts the map by whole texels, so
// shadow edges do not swim). The light-space axes depend only on the sun direction.
std::array<ShadowCascade, kShadowCascades> fitCascades(const CascadeFitDesc& desc);

// Where cascade i lies in the shadow atlas (2 × 2 tiles of resolution² texels): tile column and row. A cascade's
// clip space maps onto its tile: texel = tile · resolution + (clip.xy · 0.5 + 0.5) · resolution (row 0 at clip y −1).
inline glm::uvec2 shadowAtlasTile(uint32_t cascade) { return glm::uvec2(cascade & 1u, cascade >> 1); }

// The light's view matrix (world → light space, looking along −sunDirection) the cascades share.
glm::mat4 sunViewMatrix(const glm::vec3& sunDirection);

}  // namespace bricklight::render
