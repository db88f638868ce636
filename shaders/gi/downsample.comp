#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 1: the application's G-buffer at internal resolution, in our own encoding: device depth (sky where
// the inputs are unusable: NaN, no normal), normal + perceptual roughness packed, UV motion. One display
// pixel per internal pixel (the one under its centre), so depth and normal stay a consistent pair.
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D inputDepth;
BL_TEXTURE(1) uniform sampler2D inputNormals;
BL_TEXTURE(2) uniform sampler2D inputRoughness;
BL_TEXTURE(3) uniform sampler2D inputMotion;
BL_IMAGE(0, r32f) uniform writeonly image2D outDepth;
BL_IMAGE(1, r32ui) uniform writeonly uimage2D outSurface;
BL_IMAGE(2, rg16f) uniform writeonly image2D outMotion;

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, giFrame.size.xy))) return;
    ivec2 source = ivec2(min((vec2(pixel) + 0.5) * vec2(giFrame.size.zw) / vec2(giFrame.size.xy), vec2(giFrame.size.zw) - 1.0));
    float depth = texelFetch(inputDepth, source, 0).r;
    vec3 n = texelFetch(inputNormals, source, 0).xyz * giFrame.normalScale.xyz + giFrame.normalOffset.xyz;
    float roughness = texelFetch(inputRoughness, source, 0)[giFrame.inputs.x];
    if (giFrame.inputs.y == 0u) roughness = sqrt(max(roughness, 0.0));
    vec2 motion = texelFetch(inputMotion, source, 0).xy * giFrame.motion.xy;
    float len = length(n);
    bool usable = giFinite(depth) && giFinite(n) && len > 1e-3 && giFinite(roughness);
    if (!usable) depth = giSkyDepth();
    if (!(giFinite(motion.x) && giFinite(motion.y))) motion = vec2(0.0);
    imageStore(outDepth, ivec2(pixel), vec4(depth));
    imageStore(outSurface, ivec2(pixel), uvec4(usable ? giPackSurface(n / len, roughness) : 0u));
    imageStore(outMotion, ivec2(pixel), vec4(motion, 0.0, 0.0));
}
