#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "bricklight/reflection_ray.glsl"
#include "gi_common.glsl"
#include "gi_alpha.glsl"
// Hybrid reflections' distance-field rays (gi::GiContext::traceReflectionRays): dispatched indirectly over a list of
// display pixels, 64 per group. Each traces its pixel's reflection ray (bricklight/reflection_ray.glsl, the same ray
// the screen-space trace followed) through the whole field and reads the radiance cache at the hit, as the probes'
// rays do; the environment where it leaves the field. The G-buffer is the application's, at display size.
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
BL_CONSTANTS(2) uniform Pass {
    uvec4 list;  // x: the word of the count buffer that holds the number of entries, y: frame index of the rays
} pass;
BL_TEXTURE(0) uniform sampler2D inputDepth;
BL_TEXTURE(1) uniform sampler2D inputNormals;
BL_TEXTURE(2) uniform sampler2D inputRoughness;
BL_READ_BUFFER(0) Rays { uint rays[]; };
BL_READ_BUFFER(1) Count { uint count[]; };
BL_IMAGE(0, rgba16f) uniform image2D reflections;
BL_IMAGE(1, r32ui) uniform readonly uimage3D giRadianceCache;
#include "gi_environment.glsl"
#define GI_USES_RADIANCE_CACHE
#include "gi_bricks.glsl"

void main() {
    uint index = gl_WorkGroupID.x * 64u + gl_LocalInvocationID.x;
    if (index >= count[pass.list.x]) return;
    uint entry = rays[index];
    if (entry == 0xFFFFFFFFu) return;  // a helper entry of a padded list
    uvec2 pixel = uvec2(entry & 0x7FFFu, (entry >> 15u) & 0x3FFFu);
    uvec2 size = giFrame.size.zw;
    if (any(greaterThanEqual(pixel, size))) return;
    float depth = texelFetch(inputDepth, ivec2(pixel), 0).r;
    vec3 n = texelFetch(inputNormals, ivec2(pixel), 0).xyz * giFrame.normalScale.xyz + giFrame.normalOffset.xyz;
    float roughness = texelFetch(inputRoughness, ivec2(pixel), 0)[giFrame.inputs.x];
    if (giFrame.inputs.y == 0u) roughness = sqrt(max(roughness, 0.0));
    vec4 result = vec4(0.0);
    if (!giIsSky(depth) && giFinite(n) && length(n) > 1e-3 && giFinite(roughness)) {
        vec3 p = giWorldPosition((vec2(pixel) + 0.5) / vec2(size), depth, giCamera.inverseViewProjection);
        n = normalize(n);
        vec3 toEye = normalize(giFrame.camera.xyz - p);
        if (dot(n, toEye) < 0.0) n = -n;
        roughness = clamp(roughness, 0.0, 1.0);
        vec3 d = blReflectionDirection(pixel, pass.list.y, n, toEye, roughness);
        BlSdfRay ray = giMakeSpecularRay(p + n * giPushOff(p, giFrame.trace.y), d, giFrame.trace.w, max(roughness * roughness, 1e-3));
        uint rng = giPcg(giPcg(pixel.y * size.x + pixel.x) ^ (pass.list.y * 0x9e3779b9u));
        BlSdfHit hit = giTraceThroughAlpha(ray, rng);
        vec3 radiance;
        if (hit.gaveUp) {
            result = vec4(0.0);  // no answer: the composite keeps the GI's specular here
        } else if (!hit.hit) {
            result = vec4(giMissRadiance(d), 1.0);
        } else if (giRadianceAt(ray.origin + d * hit.t, hit.brickId, hit.brickUvw, hit.cascade, radiance)) {
            result = vec4(radiance, 1.0);
        }
    }
    imageStore(reflections, ivec2(pixel), result);
    // Quad neighbours that wanted a reflection but got no ray of their own take this one's (copy flags).
    for (uint k = 0u; k < 3u; ++k) {
        if ((entry & (1u << (29u + k))) == 0u) continue;
        uvec2 other = pixel ^ uvec2(k != 1u ? 1u : 0u, k != 0u ? 1u : 0u);
        if (all(lessThan(other, size))) imageStore(reflections, ivec2(other), result);
    }
}
