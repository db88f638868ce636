#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
// Pass 8: trace the screen probes. One group per probe, one ray per texel (jittered within the texel,
// equal-area hemisphere mapping around the probe normal): a hit reads the radiance cache at the hit (the
// finest cascade with data there), a miss the environment. New probes take the result; reprojected probes
// retrace a quarter of their texels (one of each 2×2 block, rotating per frame) and blend them in. A hit with no
// cached radiance anywhere keeps the texel's old value, or is marked "hit, unknown" (alpha, see
// gi_common.glsl) for project_probes to fill with the mean of the probe's known hits — not left out, which
// would weigh the misses (the environment) too much.
layout(local_size_x = 8, local_size_y = 8) in;
#define GI_PROBE_BLEND 0.35  // weight of a retraced texel's new sample in a reprojected probe
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_IMAGE(0, rgba16f) uniform image2D probes;
BL_IMAGE(1, r32ui) uniform readonly uimage3D giRadianceCache;
#include "gi_environment.glsl"
#define GI_USES_RADIANCE_CACHE
#include "gi_bricks.glsl"

void main() {
    uvec2 tile = gl_WorkGroupID.xy;
    uvec4 info = probeInfo[tile.y * giFrame.tiles.x + tile.x];
    ivec2 texel = ivec2(tile * 8u + gl_LocalInvocationID.xy);
    if ((info.w & GI_PROBE_VALID) == 0u) {
        imageStore(probes, texel, vec4(0.0));
        return;
    }
    bool reprojected = (info.w & GI_PROBE_REPROJECTED) != 0u;
    vec4 old = imageLoad(probes, texel);
    // Reprojected probes retrace one texel of each 2×2 block per frame (all four within four frames).
    uint phase = (gl_LocalInvocationID.x & 1u) + 2u * (gl_LocalInvocationID.y & 1u);
    if (reprojected && old.a > 0.0 && phase != (giFrameIndex() & 3u)) return;
    uint rng = giPcg(giPcg(tile.y * giFrame.tiles.x + tile.x) ^ (giFrameIndex() * 64u + gl_LocalInvocationIndex));
    vec2 u = (vec2(gl_LocalInvocationID.xy) + vec2(giRandom(rng), giRandom(rng))) / 8.0;
    vec3 n = giProbeNormal(info);
    vec3 d = giProbeDirection(n, u);
    uvec2 pixel = giProbePixel(info);
    vec3 p = giWorldPosition(giPixelUv(pixel), uintBitsToFloat(info.y), giCamera.inverseViewProjection);
    BlSdfRay ray = blSdfMakeRay(p + n * giPushOff(p, giFrame.trace.x), d, giFrame.trace.z, giFrame.trace.w);
    ray.startCascade = giFrame.cascades.x;
    ray.endCascade = giFrame.cascades.y;
    ray.epsilonScale = giFrame.epsilon.x;
    BlSdfHit hit = blSdfTrace(ray);
    vec3 radiance;
    float kind = GI_TEXEL_HIT;
    if (!hit.hit) {
        radiance = giEnvironment(d);
        kind = GI_TEXEL_MISS;
    } else if (!giRadianceAt(ray.origin + d * hit.t, hit.brickId, hit.brickUvw, hit.cascade, radiance)) {
        // A surface no view has lit yet: keep what the texel had, else mark it for the projection pass
        // to fill from the probe's other hits.
        if (!(reprojected && old.a > 0.0)) imageStore(probes, texel, vec4(0.0, 0.0, 0.0, GI_TEXEL_UNKNOWN_HIT));
        return;
    }
    vec4 value = vec4(radiance, kind);
    if (reprojected && old.a > GI_TEXEL_UNKNOWN_HIT) value.rgb = mix(old.rgb, radiance, GI_PROBE_BLEND);
    imageStore(probes, texel, value);
}
