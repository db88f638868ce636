#version 450
#extension GL_GOOGLE_include_directive : require
// The benchmark's emittance: a grey surface under the sun of the benchmark's G-buffer, unshadowed (an
// application would shadow it with its shadow maps; the renderer's hook traces rays).
#include "bricklight/voxelize.glsl"
BL_CONSTANTS(0) uniform Sun {
    vec4 direction;  // xyz towards the sun
    vec4 radiance;   // rgb: albedo / π × irradiance
} sun;

vec3 blVoxelEmittance(BlVoxelFragment f) { return sun.radiance.rgb * max(dot(f.normal, sun.direction.xyz), 0.0); }
