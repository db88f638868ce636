#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The hit mask (one bit per pixel, 8×4 pixels per texel) to a shadow mask (shadows::ShadowClassifier::resolve):
// 1 lit, 0 shadowed or facing away; −1 where not sure (ShadowClassifyDesc::markUnsurePixels).
layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;  // large groups: small ones are launch-bound
#include "shadow_params.glsl"
BL_IMAGE(0, r32ui) uniform readonly uimage2D hitMask;
BL_IMAGE(1, r16f) uniform writeonly image2D shadowMask;
BL_IMAGE(2, r32ui) uniform readonly uimage2D sureMask;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), params.size.xy))) return;
    uint bits = imageLoad(hitMask, pixel / ivec2(8, 4)).x;
    uint bit = 1u << uint((pixel.y & 3) * 8 + (pixel.x & 7));
    // Unsure pixels (with markUnsurePixels): −1, for the application's own shadow-map answer.
    bool unsure = (params.size.w & 2u) != 0u && (imageLoad(sureMask, pixel / ivec2(8, 4)).x & bit) == 0u;
    imageStore(shadowMask, pixel, vec4(unsure ? -1.0 : ((bits & bit) != 0u ? 0.0 : 1.0)));
}
