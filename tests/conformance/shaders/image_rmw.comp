#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Read-modify-write of an r32ui image: v = v * 3 + add.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params { ivec2 size; uint add; } params;
BL_IMAGE(0, r32ui) uniform uimage2D image;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, params.size))) return;
    uint v = imageLoad(image, p).x;
    imageStore(image, p, uvec4(v * 3u + params.add));
}
