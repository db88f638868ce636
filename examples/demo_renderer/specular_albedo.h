// The split-sum scale and bias of the renderer's specular lobe (scene_trace.glsl's evalBrdf: GGX with α = roughness²,
// height-correlated Smith visibility, Schlick Fresnel): the composite multiplies the GI's and the reflections'
// prefiltered light by F0 · A + B, so that a mirror of constant surroundings sends back exactly what the path
// tracer's BRDF does. Integrated here once, not fitted: the common analytic fit (Karis' for Unreal's mobile path)
// is for another visibility term and read 14 % below this lobe's directional albedo at roughness 0.3.
#pragma once

#include <cstdint>
#include <vector>

namespace bricklight::render {

constexpr uint32_t kSpecularAlbedoSize = 32;  // texels along n·v (x) and perceptual roughness (y)

// (A, B) per texel, row-major, x = n·v and y = roughness sampled at texel centres ((i + 0.5) / size): the directional
// albedo of the specular lobe is F0 · A + B for Schlick's F = F0 + (1 − F0)(1 − v·h)⁵. Deterministic (a fixed
// Hammersley set per texel).
std::vector<float> specularAlbedoTable();

}  // namespace bricklight::render
