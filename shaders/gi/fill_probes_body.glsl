// Included by fill_probes.comp and fill_probes_vct.comp (which defines GI_UNSEEN_FROM_VCT).
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_alpha.glsl"
// Pass 8: trace the screen probes. 16 threads per probe (4 probes per group), one ray per traced texel
// (jittered within the texel, equal-area hemisphere mapping around the probe normal): a hit reads the
// radiance cache at the hit (the finest cascade with data there), a miss the environment. Every probe
// traces a quarter of its texels a frame (one of each 2×2 block, rotating per frame); a reprojected probe
// keeps the others, a new one leaves them empty until their turn. A hit with no
// cached radiance anywhere is marked "hit, unknown" (alpha, see gi_common.glsl) for project_probes to fill
// from the known hits of its neighbouring texels or the probe's — not left out, which would weigh the
// misses (the environment) too much.
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
#ifdef GI_UNSEEN_FROM_VCT  // hits no view has lit read a voxel clip-map's light (DispatchDesc::unseenLight)
#define BL_CONE_TRACE_TEXTURE_BASE 0  // 0..6 (13..15 are the environment and the field's atlas)
#define BL_CONE_TRACE_FRAME_SLOT 1
#include "bricklight/cone_trace.glsl"
#endif

// One texel: trace its ray (jittered within the texel) and store or blend the result.
void giFillTexel(uvec2 tile, uint probeIndex, uvec4 info, uvec2 local, bool reprojected, vec4 old) {
    ivec2 texel = ivec2(tile * 8u + local);
    uint rng = giPcg(giPcg(probeIndex) ^ (giFrameIndex() * 64u + local.y * 8u + local.x));
    vec2 u = (vec2(local) + vec2(giRandom(rng), giRandom(rng))) / 8.0;
    vec3 n = giProbeNormal(info);
    vec3 d = giProbeDirection(n, u);
    uvec2 pixel = giProbePixel(info);
    vec3 p = giWorldPosition(giPixelUv(pixel), uintBitsToFloat(info.y), giCamera.inverseViewProjection);
    BlSdfRay ray = giMakeRay(p + n * giPushOff(p, giFrame.trace.x), d, giFrame.trace.w, GI_RAY_DIFFUSE);
    BlSdfHit hit = giTraceThroughAlpha(ray, rng);
    vec3 radiance;
    float kind = GI_TEXEL_HIT;
    if (hit.gaveUp) {
        // Out of iterations before any answer: neither the sky nor a known surface (like an unknown hit).
        imageStore(probes, texel, vec4(0.0, 0.0, 0.0, GI_TEXEL_UNKNOWN_HIT));
        return;
    }
    if (!hit.hit) {
        radiance = giEnvironment(d);
        kind = GI_TEXEL_MISS;
    } else if (!giRadianceAtSide(ray.origin + d * hit.t, hit.brickId, hit.brickUvw, hit.cascade, hit.alphaTested ? hit.normal : vec3(0.0),
                                 radiance)) {
#ifdef GI_UNSEEN_FROM_VCT
        // The clip-map's voxels hold the light of surfaces the camera never saw (voxelized from the app's draws).
        bool known;
        radiance = blVctSurfaceRadiance(ray.origin + d * hit.t, d, known);
        if (known && giFinite(radiance)) {
            vec4 v = vec4(radiance, kind);
            if (reprojected && old.a > GI_TEXEL_UNKNOWN_HIT) v.rgb = mix(old.rgb, radiance, GI_PROBE_BLEND);
            imageStore(probes, texel, v);
            return;
        }
#endif
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

// 16 threads per probe, one per 2×2 block of texels, one ray per thread and frame: every probe, new or
// reprojected, traces one texel of each block (rotating per frame, all four within four frames). A new
// probe's other texels stay empty until their turn; the projection scales the traced ones up to the whole
// hemisphere. (New probes tracing all 64 texels at once made their SIMD groups trace four rays in series,
// and those groups set the pass's time.)
void main() {
    uint probeIndex = (gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x) * 4u + gl_LocalInvocationIndex / 16u;
    if (probeIndex >= giFrame.tiles.x * giFrame.tiles.y) return;
    uvec2 tile = uvec2(probeIndex % giFrame.tiles.x, probeIndex / giFrame.tiles.x);
    uvec4 info = probeInfo[probeIndex];
    uint block = gl_LocalInvocationIndex % 16u;
    uvec2 base = uvec2(block % 4u, block / 4u) * 2u;
    bool valid = (info.w & GI_PROBE_VALID) != 0u;
    bool reprojected = (info.w & GI_PROBE_REPROJECTED) != 0u;
    uint turn = giFrameIndex() & 3u;
    for (uint k = 0u; k < 4u; ++k) {
        uvec2 local = base + uvec2(k & 1u, k >> 1);
        ivec2 texel = ivec2(tile * 8u + local);
        if (!valid || (k != turn && !reprojected)) imageStore(probes, texel, vec4(0.0));  // GI_TEXEL_EMPTY
    }
    if (!valid) return;
    uvec2 local = base + uvec2(turn & 1u, turn >> 1);
    vec4 old = reprojected ? imageLoad(probes, ivec2(tile * 8u + local)) : vec4(0.0);
    giFillTexel(tile, probeIndex, info, local, reprojected, old);
}
