#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Passes 15/16: separable bilateral blur of diffuse and specular GI (direction in the pass constants).
// The radius follows the diffuse sample count: 4 pixels for fresh history, 1 when converged. Taps count
// by a Gaussian, by closeness to the pixel's plane and by normal similarity; specular taps also by
// similar roughness, and their radius shrinks with roughness (sharp reflections stay sharp). The output
// keeps the input's alpha (the sample count).
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(2) uniform Pass { ivec4 direction; } pass;  // xy step
BL_TEXTURE(0) uniform sampler2D diffuseIn;
BL_TEXTURE(1) uniform sampler2D specularIn;
BL_TEXTURE(2) uniform sampler2D depthNow;
BL_TEXTURE(3) uniform usampler2D surfaceNow;
BL_IMAGE(0, rgba16f) uniform writeonly image2D diffuseOut;
BL_IMAGE(1, rgba16f) uniform writeonly image2D specularOut;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), giFrame.size.xy))) return;
    vec4 d0 = texelFetch(diffuseIn, pixel, 0), s0 = texelFetch(specularIn, pixel, 0);
    float depth = texelFetch(depthNow, pixel, 0).r;
    if (giIsSky(depth)) {
        imageStore(diffuseOut, pixel, d0);
        imageStore(specularOut, pixel, s0);
        return;
    }
    uint surface = texelFetch(surfaceNow, pixel, 0).r;
    vec3 p = giWorldPosition(giPixelUv(uvec2(pixel)), depth, giCamera.inverseViewProjection);
    vec3 n = giSurfaceNormal(surface);
    float roughness = giSurfaceRoughness(surface);
    float distance = length(p - giFrame.camera.xyz);
    float radius = mix(4.0, 1.0, clamp(d0.a / 16.0, 0.0, 1.0));
    int taps = int(ceil(radius));
    float specularRadius = radius * clamp(roughness * 2.0, 0.0, 1.0);
    vec3 dsum = vec3(0.0), ssum = vec3(0.0);
    float dw = 0.0, sw = 0.0;
    for (int i = -taps; i <= taps; ++i) {
        ivec2 q = pixel + pass.direction.xy * i;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), giFrame.size.xy))) continue;
        float dq = texelFetch(depthNow, q, 0).r;
        if (giIsSky(dq)) continue;
        uint sq = texelFetch(surfaceNow, q, 0).r;
        vec3 pq = giWorldPosition(giPixelUv(uvec2(q)), dq, giCamera.inverseViewProjection);
        float plane = abs(dot(pq - p, n)) / (0.005 * distance + 1e-6);
        float geometry = exp(-plane * plane) * pow(max(dot(n, giSurfaceNormal(sq)), 0.0), 16.0);
        float x = float(i) / radius;
        float w = exp(-2.0 * x * x) * geometry;
        vec4 dv = texelFetch(diffuseIn, q, 0);
        if (dv.a > 0.0 || i == 0) {
            dsum += dv.rgb * w;
            dw += w;
        }
        float xs = specularRadius > 0.0 ? float(i) / specularRadius : (i == 0 ? 0.0 : 1e3);
        float ws = exp(-2.0 * xs * xs) * geometry * exp(-abs(giSurfaceRoughness(sq) - roughness) * 10.0);
        vec4 sv = texelFetch(specularIn, q, 0);
        if (sv.a > 0.0 || i == 0) {
            ssum += sv.rgb * ws;
            sw += ws;
        }
    }
    imageStore(diffuseOut, pixel, vec4(dw > 0.0 ? dsum / dw : d0.rgb, d0.a));
    imageStore(specularOut, pixel, vec4(sw > 0.0 ? ssum / sw : s0.rgb, s0.a));
}
