#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The shadow denoiser's pass for the tiles the classifier did not list (shadows::ShadowDenoiser): their pixels take
// the hit mask's decided answer as the output, and as a history of one frame with this frame's geometry, so that a
// tile listed next frame reprojects into a consistent history. Listed tiles' pixels are left to the temporal and
// filter passes. Large groups: small ones are launch-bound.
layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;
#include "denoise_shadows_common.glsl"
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_TEXTURE(1) uniform sampler2D normalTexture;
BL_IMAGE(0, r32ui) uniform readonly uimage2D hitMask;
BL_IMAGE(1, rgba16f) uniform writeonly image2D history;
BL_IMAGE(2, rg32ui) uniform writeonly uimage2D geometry;
BL_IMAGE(3, r32ui) uniform readonly uimage2D listedTiles;
BL_IMAGE(4, r16f) uniform writeonly image2D shadowMask;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), params.size.xy))) return;
    ivec2 tile = pixel / ivec2(8, 4);
    if (imageLoad(listedTiles, tile).x != 0u) return;
    float depth = texelFetch(depthTexture, pixel, 0).r;
    vec3 n = normalize(texelFetch(normalTexture, pixel, 0).xyz * params.normalScale.xyz + params.normalBias.xyz);
    float answer = blDenoiseAnswer(imageLoad(hitMask, tile).x, pixel);
    imageStore(geometry, pixel, uvec4(floatBitsToUint(depth), blDenoisePackNormal(n), 0u, 0u));
    imageStore(history, pixel, vec4(answer, answer, 1.0, 0.0));
    imageStore(shadowMask, pixel, vec4(answer));
}
