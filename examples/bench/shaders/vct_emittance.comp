#version 450
#extension GL_GOOGLE_include_directive : require
// The benchmark's emittance for the compute voxelizer (vct::VoxelMaterial::computeShader): the same hook as
// vct_emittance.frag, compiled into our compute voxelization.
#include "bricklight/voxelize_compute.glsl"
BL_CONSTANTS(0) uniform Sun {
    vec4 direction;  // xyz towards the sun
    vec4 radiance;   // rgb: albedo / π × irradiance
} sun;

vec3 blVoxelEmittance(BlVoxelFragment f) { return sun.radiance.rgb * max(dot(f.normal, sun.direction.xyz), 0.0); }
