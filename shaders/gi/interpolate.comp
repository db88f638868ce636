#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#define GI_USES_CHANGED_REGIONS
#include "gi_common.glsl"
#include "gi_sh.glsl"
// Pass 14: resolve each pixel's GI and accumulate it over time. Diffuse: the irradiance SH (the screen
// probes, which hold the world cache's share; the world cache alone where no probe is usable) for the
// pixel's normal, as irradiance / π. Specular: the traced value where the specular
// trace found one, else the SH seen through the roughness lobe along the reflection (both read from the
// caches' SH at once: gi_irradiance.glsl). Both blend into the
// reprojected history (alpha = sample count, capped at kMaxDiffuseHistory (16), specular also at 8..64 by roughness for
// specular); a value far from the history (relative change > 1/2) cuts the count to 4 so that changes of
// light show within a few frames instead of ghosting.
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D depthNow;
BL_TEXTURE(1) uniform usampler2D surfaceNow;
BL_TEXTURE(2) uniform sampler2D specularTraced;
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_READ_BUFFER(1) ProbeIrradianceSH { vec4 probeIrradianceSH[]; };
BL_READ_BUFFER(2) BrickSH { uvec2 giBrickSH[]; };
BL_IMAGE(0, rgba16f) uniform image2D diffuseHistory;
BL_IMAGE(1, rgba16f) uniform image2D specularHistory;
#define GI_USES_BRICK_SH
#include "gi_bricks.glsl"
#include "gi_irradiance.glsl"

vec4 giAccumulate(vec4 history, vec3 value, float maxCount) {
    if (!giFinite(value)) value = history.a > 0.0 ? history.rgb : vec3(0.0);
    float count = min(history.a + 1.0, maxCount);
    float lh = dot(history.rgb, vec3(0.3, 0.6, 0.1)), lv = dot(value, vec3(0.3, 0.6, 0.1));
    if (history.a > 0.0 && abs(lh - lv) > 0.5 * max(max(lh, lv), 1e-4) && abs(lh - lv) > 0.05 * (lh + lv) + 1e-3)
        count = min(count, 4.0);
    return vec4(mix(history.rgb, value, 1.0 / count), count);
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, giFrame.size.xy))) return;
    float depth = texelFetch(depthNow, ivec2(pixel), 0).r;
    if (giIsSky(depth)) {
        imageStore(diffuseHistory, ivec2(pixel), vec4(0.0));
        imageStore(specularHistory, ivec2(pixel), vec4(0.0));
        return;
    }
    uint surface = texelFetch(surfaceNow, ivec2(pixel), 0).r;
    vec3 p = giWorldPosition(giPixelUv(pixel), depth, giCamera.inverseViewProjection);
    vec3 n = giSurfaceNormal(surface);
    vec3 toEye = normalize(giFrame.camera.xyz - p);
    if (dot(n, toEye) < 0.0) n = -n;
    float roughness = giSurfaceRoughness(surface);
    vec3 r = reflect(-toEye, n);
    GiShReads reads;
    giShDiffuseWeights(n, reads.diffuse);
    giShLobeWeights(r, roughness, reads.lobe);
    vec3 irradiance, lobe;
    bool have = giIrradiance(pixel, p, n, reads, irradiance, lobe);
    vec4 diffuse = imageLoad(diffuseHistory, ivec2(pixel));
    // Where geometry just changed (a mover's old and new place) the history is cut short, so that the light
    // follows the mover instead of trailing it.
    bool changed = giInChangedRegion(p, p, 1e30);
    if (changed) diffuse.a = min(diffuse.a, GI_CHANGE_HISTORY - 1.0);
    if (have) diffuse = giAccumulate(diffuse, irradiance, float(giFrame.inputs.w));
    imageStore(diffuseHistory, ivec2(pixel), diffuse);

    vec4 traced = texelFetch(specularTraced, ivec2(pixel), 0);
    vec3 value = traced.a > 0.0 ? traced.rgb : lobe;
    vec4 specular = imageLoad(specularHistory, ivec2(pixel));
    if (changed) specular.a = min(specular.a, GI_CHANGE_HISTORY - 1.0);
    if (traced.a > 0.0 || have) specular = giAccumulate(specular, value, min(mix(8.0, 64.0, sqrt(roughness)), float(giFrame.inputs.w)));
    imageStore(specularHistory, ivec2(pixel), specular);
}
