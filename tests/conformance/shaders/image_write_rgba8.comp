#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Writes a position-derived pattern into an rgba8 storage image.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params { ivec2 size; uint seed; } params;
BL_IMAGE(0, rgba8) uniform writeonly image2D target;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, params.size))) return;
    uint v = uint(p.x * 7 + p.y * 13) + params.seed;
    imageStore(target, p, vec4(float(v & 255u), float((v * 3u) & 255u), float(p.x & 255), float(p.y & 255)) / 255.0);
}
