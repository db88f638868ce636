// The G-buffer and camera every screen-space technique reads — GI, voxel cone tracing, the shadow and reflection
// classifiers and their denoisers — described once: each technique's per-frame description holds a
// gbuffer::Camera and a gbuffer::Inputs and reads the fields it needs (its table says which). The conventions are
// the library's (docs/gi.md, "Conventions"): right-handed world, OpenGL-style clip space with depth in [0, 1].
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "bricklight/rhi.h"

namespace bricklight::gbuffer {

// This frame's camera and the previous frame's (the reprojections go through both view-projections).
struct Camera {
    glm::mat4 view{1.0f}, projection{1.0f};
    glm::mat4 previousView{1.0f}, previousProjection{1.0f};
    // Depth 1 near, 0 far: read by the classifiers and denoisers. GI fixes it at creation
    // (gi::ContextFlags::ReversedDepth); the cone tracer takes forward depth only.
    bool reversedDepth = false;
};

// The G-buffer, at the technique's size unless its table says otherwise.
struct Inputs {
    rhi::TextureHandle depth;  // one channel of device depth (D32_FLOAT or R32_FLOAT; GI also R16_FLOAT)
    // World normal in xyz = stored × normalsUnpackScale + normalsUnpackOffset; the default unpacks an 8-bit UNORM
    // normal, float normals take {1}, {0}.
    rhi::TextureHandle normals;
    glm::vec3 normalsUnpackScale{2.0f}, normalsUnpackOffset{-1.0f};
    rhi::TextureHandle roughness;  // any float/unorm texture; one channel is roughness
    uint32_t roughnessChannel = 0;    // 0..3
    bool roughnessPerceptual = true;  // true: the channel holds perceptual roughness; false: GGX α (its square)
    // Optional: UV-space motion (current − previous) in xy, times motionVectorScale (previous UV = UV − motion;
    // the cone tracer takes a scale of 1 only). Without them the world is taken as still and the motion comes
    // from depth and the two cameras.
    rhi::TextureHandle motionVectors;
    glm::vec2 motionVectorScale{1.0f};
};

}  // namespace bricklight::gbuffer
