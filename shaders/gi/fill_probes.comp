#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
// Pass 8: trace the screen probes. 16 threads per probe (4 probes per group), one ray per traced texel (jittered within the texel,
// equal-area hemisphere mapping around the probe normal): a hit reads the radiance cache at the hit (the
// finest cascade with data there), a miss the environment. New probes take the result; reprojected probes
// retrace a quarter of their texels (one of each 2×2 block, rotating per frame). A hit with no
// cached radiance anywhere is marked "hit, unknown" (alpha, see gi_common.glsl) for project_probes to fill
// with the mean of the probe's known hits — not left out, which would weigh the misses (the environment)
// too much.
layout(local_size_x = 64) in;
// Weight of a retraced texel's new sample in a reprojected probe. 1: the texel keeps one sample, the
// newest; averaging over frames is the interpolation pass's job. (An average here, 0.35, biased probes
// towards misses: the open furnace gave 0.63 of the path tracer's hit fraction instead of 0.98.)
#define GI_PROBE_BLEND 1.0
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_IMAGE(0, rgba16f) uniform image2D probes;
BL_IMAGE(1, r32ui) uniform readonly uimage3D giRadianceCache;
#include "gi_environment.glsl"
#define GI_USES_RADIANCE_CACHE
#include "gi_bricks.glsl"

// One texel: trace its ray (jittered within the texel) and store or blend the result.
void giFillTexel(uvec2 tile, uint probeIndex, uvec4 info, uvec2 local, bool reprojected, vec4 old) {
    ivec2 texel = ivec2(tile * 8u + local);
    uint rng = giPcg(giPcg(probeIndex) ^ (giFrameIndex() * 64u + local.y * 8u + local.x));
    vec2 u = (vec2(local) + vec2(giRandom(rng), giRandom(rng))) / 8.0;
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
        // A surface no view has lit yet: marked for the projection pass to fill from the probe's known
        // hits. (Keeping a reprojected texel's old value instead biased probes dark: that value may have
        // come through another probe's directions, often a miss.)
        imageStore(probes, texel, vec4(0.0, 0.0, 0.0, GI_TEXEL_UNKNOWN_HIT));
        return;
    }
    vec4 value = vec4(radiance, kind);
    if (reprojected && old.a > GI_TEXEL_UNKNOWN_HIT) value.rgb = mix(old.rgb, radiance, GI_PROBE_BLEND);
    imageStore(probes, texel, value);
}

// 16 threads per probe, one per 2×2 block of texels, so that the traced rays fill whole SIMD groups:
// a reprojected probe retraces one texel of each block per frame (all four within four frames), a new
// probe all four.
void main() {
    uint probeIndex = (gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x) * 4u + gl_LocalInvocationIndex / 16u;
    if (probeIndex >= giFrame.tiles.x * giFrame.tiles.y) return;
    uvec2 tile = uvec2(probeIndex % giFrame.tiles.x, probeIndex / giFrame.tiles.x);
    uvec4 info = probeInfo[probeIndex];
    uint block = gl_LocalInvocationIndex % 16u;
    uvec2 base = uvec2(block % 4u, block / 4u) * 2u;
    bool reprojected = (info.w & GI_PROBE_REPROJECTED) != 0u;
    for (uint k = 0u; k < 4u; ++k) {
        uvec2 local = base + uvec2(k & 1u, k >> 1);
        ivec2 texel = ivec2(tile * 8u + local);
        if ((info.w & GI_PROBE_VALID) == 0u) {
            imageStore(probes, texel, vec4(0.0));
            continue;
        }
        vec4 old = imageLoad(probes, texel);
        if (reprojected && old.a > 0.0 && k != (giFrameIndex() & 3u)) continue;
        giFillTexel(tile, probeIndex, info, local, reprojected, old);
    }
}
