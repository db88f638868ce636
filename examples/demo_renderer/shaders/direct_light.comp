#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Direct lighting of the G-buffer: per pixel, emission plus light straight from the emitters (next-event
// estimation, `samples` emitter samples), the sun and the sky (BRDF-sampled visibility), with
// ray-traced shadows against the scene's BVH. The same estimator as the path tracer's first vertex, so the
// two agree up to noise. Writes the direct radiance (w = 1) per pixel. With the sun's shadow from cascaded
// shadow maps (--shadows shadowmap) the host zeroes the sun here and shadow_sun_light.comp adds it afterwards.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    mat4 inverseViewProjection;
    vec4 eye;
    uvec4 size;  // xy image size, z samples per pixel, w frame
} params;
BL_TEXTURE(0) uniform sampler2D gAlbedo;
BL_TEXTURE(1) uniform sampler2D gNormal;
BL_TEXTURE(2) uniform sampler2D gEmission;
BL_TEXTURE(3) uniform sampler2D gPosition;  // w = 1 where geometry was drawn
BL_STORAGE_BUFFER(0) Output { vec4 radiance[]; };
#include "scene_trace.glsl"

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    uint index = pixel.y * params.size.x + pixel.x;
    vec4 position = texelFetch(gPosition, ivec2(pixel), 0);
    if (position.w == 0.0) {  // nothing drawn: the sky
        radiance[index] = vec4(sceneLight.sky.rgb, 1.0);
        return;
    }
    vec3 p = position.xyz;
    vec4 normal = texelFetch(gNormal, ivec2(pixel), 0);
    vec4 albedo = texelFetch(gAlbedo, ivec2(pixel), 0);
    vec4 emission = texelFetch(gEmission, ivec2(pixel), 0);
    vec3 n = normalize(normal.xyz);
    Surface surface;
    surface.baseColor = albedo.rgb;
    surface.roughness = albedo.a;
    surface.metalness = emission.a;
    surface.dielectricF0 = normal.w;
    vec3 v = normalize(params.eye.xyz - p);
    float eps = sceneLight.lightWeight.y;
    rngState = pcg(index ^ pcg(params.size.w + pcg(sceneLight.counts.y)));
    vec3 sum = vec3(0.0);
    uint samples = max(params.size.z, 1u);
    for (uint s = 0u; s < samples; ++s) {
        sum += directLight(p, n, v, surface, eps);
        vec3 d, weight;
        if (any(greaterThan(sceneLight.sky.rgb, vec3(0.0))) && sampleBrdf(surface, n, v, d, weight)) {
            Hit h;
            if (!traceRay(p, d, eps, 1e30, true, h)) sum += weight * sceneLight.sky.rgb;
        }
    }
    radiance[index] = vec4(emission.rgb + sum / float(samples), 1.0);
}
