#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// GL smoke test: writes texel (x, y) = x + 1000 * y + 7 into an r32ui storage image.
layout(local_size_x = 8, local_size_y = 8) in;
BL_IMAGE(0, r32ui) uniform writeonly uimage2D image;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(p, imageSize(image)))) imageStore(image, p, uvec4(uint(p.x) + 1000u * uint(p.y) + 7u));
}
