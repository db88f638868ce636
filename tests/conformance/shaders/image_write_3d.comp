#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Writes value = x + 100 y + 10000 z into an r32ui 3D storage image (one mip).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
BL_CONSTANTS(0) uniform Params { ivec4 size; } params;
BL_IMAGE(0, r32ui) uniform writeonly uimage3D target;
void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, params.size.xyz))) return;
    imageStore(target, p, uvec4(uint(p.x + 100 * p.y + 10000 * p.z) + uint(params.size.w)));
}
