#version 450
#extension GL_GOOGLE_include_directive : require
// An emittance function that sends its fragment's world position (tests check what the hook is given).
#include "bricklight/voxelize.glsl"

vec3 blVoxelEmittance(BlVoxelFragment f) { return f.position; }
