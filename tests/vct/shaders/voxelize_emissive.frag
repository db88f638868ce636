#version 450
#extension GL_GOOGLE_include_directive : require
// An application's emittance function as tests write it: every surface sends the same radiance (constants
// slot 0), the light of VXGI's emissive test cube.
#include "bricklight/voxelize.glsl"
BL_CONSTANTS(0) uniform Emission { vec4 radiance; } emission;

vec3 blVoxelEmittance(BlVoxelFragment f) { return emission.radiance.rgb; }
