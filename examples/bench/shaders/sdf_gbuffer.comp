#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
// The benchmark's G-buffer, traced through the distance field instead of rasterized (so that the benchmark
// needs no scene renderer): device depth, world normal + roughness, UV motion from the previous camera,
// and a lit image (a sun with a little sky light on a grey surface) for GI to inject.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    mat4 viewProjection;
    mat4 inverseViewProjection;
    mat4 previousViewProjection;
    vec4 eye;   // xyz camera, w roughness
    uvec4 size; // xy
} params;
BL_IMAGE(0, r32f) uniform writeonly image2D depthOut;
BL_IMAGE(1, rgba16f) uniform writeonly image2D normalOut;
BL_IMAGE(2, rg16f) uniform writeonly image2D motionOut;
BL_IMAGE(3, rgba16f) uniform writeonly image2D litOut;

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(params.size.xy);
    vec4 far = params.inverseViewProjection * vec4(uv * 2.0 - 1.0, 0.5, 1.0);
    vec3 d = normalize(far.xyz / far.w - params.eye.xyz);
    // A tenth of the usual hit epsilon: the default stops up to 0.6 brixel short of the surface, which is farther
    // than a rasterized G-buffer's positions ever are, and farther than GI's camera self-check allows (half a
    // brixel) before it takes a depth buffer for one drawn with another camera.
    BlSdfRay ray = blSdfMakeRay(params.eye.xyz, d, 0.0, 1e30);
    ray.epsilonScale = 0.1;
    BlSdfHit hit = blSdfTrace(ray);
    float depth = 1.0;
    vec3 n = vec3(0.0);
    vec2 motion = vec2(0.0);
    vec3 lit = vec3(0.3, 0.4, 0.6);
    if (hit.hit) {
        vec3 p = params.eye.xyz + d * hit.t;
        vec4 clip = params.viewProjection * vec4(p, 1.0);
        depth = clip.z / clip.w;
        vec4 previous = params.previousViewProjection * vec4(p, 1.0);
        motion = uv - (previous.xy / previous.w * 0.5 + 0.5);
        n = hit.normal;
        vec3 sun = normalize(vec3(-0.4, 1.0, 0.3));
        lit = vec3(0.6) * (max(dot(n, sun), 0.0) * 3.0 + 0.2);
    }
    imageStore(depthOut, ivec2(pixel), vec4(depth));
    imageStore(normalOut, ivec2(pixel), vec4(n, params.eye.w));
    imageStore(motionOut, ivec2(pixel), vec4(motion, 0.0, 0.0));
    imageStore(litOut, ivec2(pixel), vec4(lit, 1.0));
}
