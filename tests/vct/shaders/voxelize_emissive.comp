#version 450
#extension GL_GOOGLE_include_directive : require
// voxelize_emissive.frag's emittance function for vct::VoxelScene's compute voxelizer: every surface sends the
// radiance of constants slot 0.
#include "bricklight/voxelize_compute.glsl"
BL_CONSTANTS(0) uniform Emission { vec4 radiance; } emission;

vec3 blVoxelEmittance(BlVoxelFragment f) { return emission.radiance.rgb; }
