#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The hit mask (one bit per pixel, 8×4 pixels per texel) to a shadow mask (classify::ShadowClassifier::resolve):
// 1 lit, 0 shadowed or facing away.
layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;  // large groups: small ones are launch-bound
#include "shadow_params.glsl"
BL_IMAGE(0, r32ui) uniform readonly uimage2D hitMask;
BL_IMAGE(1, r16f) uniform writeonly image2D shadowMask;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), params.size.xy))) return;
    uint bits = imageLoad(hitMask, pixel / ivec2(8, 4)).x;
    uint bit = 1u << uint((pixel.y & 3) * 8 + (pixel.x & 7));
    imageStore(shadowMask, pixel, vec4((bits & bit) != 0u ? 0.0 : 1.0));
}
