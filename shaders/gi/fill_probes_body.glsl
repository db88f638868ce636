// Included by fill_probes{,_vct}{,_carried}.comp: _vct defines GI_UNSEEN_FROM_VCT, all but _carried GI_PROBE_PARALLAX.
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_alpha.glsl"
// Pass 8: trace the screen probes. 16 threads per probe (4 probes per group), one ray per traced texel
// (jittered within the texel, equal-area hemisphere mapping around the probe normal): a hit reads the
// radiance cache at the hit (the finest cascade with data there), a miss the environment. Every probe
// traces a quarter of its texels a frame (one of each 2×2 block, rotating per frame); a reprojected probe
// keeps the others, a new one leaves them empty until their turn. A hit with no
// cached radiance anywhere is lit where it was hit (giUnseenHitRadiance: the field's material, the lights and
// the probe's light) when relighting is on; else marked "hit, unknown" (alpha, see gi_common.glsl) for
// project_probes to fill from the known hits of its neighbouring texels or the probe's — not left out, which
// would weigh the misses (the environment) too much.
layout(local_size_x = 64) in;
// Weight of a retraced texel's new sample in a reprojected probe. 1: the texel keeps one sample, the
// newest; averaging over frames is the interpolation pass's job. (An average here, 0.35, biased probes
// towards misses: the open furnace gave 0.63 of the path tracer's hit fraction instead of 0.98.)
#define GI_PROBE_BLEND 1.0
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_IMAGE(0, rgba16f) uniform image2D probes;
BL_IMAGE(1, r32ui) uniform readonly uimage3D giRadianceCache;
BL_READ_BUFFER(2) Lights { vec4 giLights[]; };  // 4 per light (core/gi/gi_constants.h: GpuLight)
// Last frame's probeIrradianceSH (project_probes.comp), 9 per probe; read only here (the read-buffer slots are taken).
BL_STORAGE_BUFFER(0) PreviousProbeSH { vec4 previousProbeSH[]; };
#include "gi_environment.glsl"
#define GI_USES_RADIANCE_CACHE
#include "gi_bricks.glsl"
#include "gi_lights.glsl"
#include "gi_sh.glsl"
#ifdef GI_UNSEEN_FROM_VCT  // hits no view has lit read a voxel clip-map's light (DispatchDesc::unseenLight)
#define BL_CONE_TRACE_TEXTURE_BASE 0  // 0 and 1 (13..15 are the environment and the field's atlas)
#define BL_CONE_TRACE_FRAME_SLOT 1
#include "bricklight/cone_trace.glsl"
#endif

// At most this many of the frame's lights get a shadow ray at one unseen hit (giUnseenHitRadiance): with more,
// each hit takes every k-th of them from a random first, weighted by k.
#define GI_UNSEEN_HIT_LIGHTS 4u

// The light of a surface no view has lit (no cache holds it), where the probe's ray met it: its emission and
// albedo · E_lights / π, from the field's material for the hit's brick (sdf::InstanceDesc::material) and the frame's
// lights shadowed through the field (gi_lights.glsl). The emission counts where the cache holds the emission of the
// surfaces the camera saw (DispatchDesc::previousLitIncludesEmission), as known hits do. False unless the application
// says its lights hold all of its direct light (DispatchDesc::lightUnseenSurfaces: a sky it does not give would be
// missing here), where the field holds no material — and in bricks that hold cards (alpha-tested surfaces): a shadow
// ray goes through cards with the alpha cache's open fraction of each cell (gi_alpha.glsl), independently of the ray
// that could not see the hit, so with the sun behind the camera a card hidden behind other cards (shadowed in truth:
// the sun's path and the view's cross the same cards) got sun through the open fractions (the foliage scene's indirect
// light 3.2× the path tracer's instead of 1.9×).
bool giUnseenHitDirect(vec3 q, vec3 normal, uint brick, inout uint rng, out vec3 radiance, out vec3 albedo, out vec3 p) {
    radiance = albedo = p = vec3(0.0);
    if ((giFrame.relight.y & GI_RELIGHT_UNSEEN_HITS) == 0u || giBrickHoldsCards(brick)) return false;
    uvec2 material = blSdfBrickMaterial(brick);
    if ((material.x >> 24) == 0u) return false;
    albedo = unpackUnorm4x8(material.x).rgb;
    p = q + normal * giPushOff(q, giFrame.trace.x);
    uint count = giFrame.relight.x;
    vec3 direct = vec3(0.0);
    if (count > 0u) {
        uint stride = (count + GI_UNSEEN_HIT_LIGHTS - 1u) / GI_UNSEEN_HIT_LIGHTS;
        uint first = min(uint(giRandom(rng) * float(stride)), stride - 1u);
        direct = giLightIrradiance(p, normal, first, stride) * float(stride);
    }
    vec3 emitted = (giFrame.relight.y & GI_RELIGHT_LIT_HOLDS_EMISSION) != 0u && material.y != 0u ? blDecodeRgb9e5(material.y) : vec3(0.0);
    radiance = emitted + albedo * direct / GI_PI;
    return true;
}

// The probe's own irradiance of the last frame (its SH covers the whole sphere, project_probes.comp) turned to
// `normal`, over π.
vec3 giProbeIrradiance(uint probeIndex, vec3 normal) {
    vec3 indirect = vec3(0.0);
    if (previousProbeSH[probeIndex * 9u].w > 0.0) {
        float w[9];
        giShDiffuseWeights(normal, w);
        for (uint i = 0u; i < 9u; ++i) indirect += previousProbeSH[probeIndex * 9u + i].rgb * w[i];
    }
    return max(indirect, vec3(0.0));
}

// How many surfaces no view has lit an unseen path visits at most, and from which of them on it ends by Russian
// roulette (giUnseenHitRadiance).
#define GI_UNSEEN_PATH 16u
#define GI_UNSEEN_ROULETTE 2u

// The radiance leaving a surface no view has lit, where a probe's ray met it: its direct light (giUnseenHitDirect)
// and the light other surfaces send it, followed as a path of cosine-weighted rays — one per surface, each surface's
// direct light weighted by the albedos before it — that ends where it reaches a surface whose light the cache holds,
// the environment, by Russian roulette, or after GI_UNSEEN_PATH surfaces with the probe's own irradiance turned to
// the last one's normal. Light that reaches the camera around a corner has bounced among surfaces the camera never
// saw (the `corridor`: the path tracer's one bounce is a tenth of its light there). Taking the probe's irradiance at
// the first of them, as this did before, measured what they receive from each other where the probe stands, not
// where they are: the corridor's indirect light was 26 % of the path tracer's. Deterministic (the probe's and the
// frame's draws, no atomics); it costs a ray and the lights' shadow rays per surface visited, only for probe rays
// that meet such a surface.
bool giUnseenHitRadiance(vec3 q, vec3 normal, uint brick, uint probeIndex, inout uint rng, out vec3 radiance) {
    vec3 albedo, p, r;
    if (!giUnseenHitDirect(q, normal, brick, rng, radiance, albedo, p)) return false;
    // One bounce only (GI_RELIGHT_DIRECT_ONLY): no path, unless the environment is direct light here
    // (GI_RELIGHT_ENVIRONMENT_IN_DIRECT): then one ray asks whether the surface sees it.
    bool directOnly = (giFrame.relight.y & GI_RELIGHT_DIRECT_ONLY) != 0u;
    if (directOnly && (giFrame.relight.y & GI_RELIGHT_ENVIRONMENT_IN_DIRECT) == 0u) return giFinite(radiance);
    vec3 throughput = albedo;
    for (uint level = 1u; level <= GI_UNSEEN_PATH; ++level) {
        if (level == GI_UNSEEN_PATH) {
            radiance += throughput * giProbeIrradiance(probeIndex, normal);
            break;
        }
        vec3 tangent, bitangent;
        giBasis(normal, tangent, bitangent);
        float u1 = giRandom(rng), phi = 2.0 * GI_PI * giRandom(rng);
        float sr = sqrt(u1);
        vec3 d = normalize(tangent * (sr * cos(phi)) + bitangent * (sr * sin(phi)) + normal * sqrt(max(1.0 - u1, 0.0)));
        BlSdfHit hit = giTraceThroughAlpha(giMakeRay(p, d, giFrame.trace.w, GI_RAY_DIFFUSE), rng);
        if (hit.gaveUp) {
            if (!directOnly) radiance += throughput * giProbeIrradiance(probeIndex, normal);
            break;
        }
        if (!hit.hit) {
            radiance += throughput * giEnvironment(d);
            break;
        }
        if (directOnly) break;
        q = p + d * hit.t;
        if (giRadianceAtSide(q, hit.brickId, hit.brickUvw, hit.cascade, hit.alphaTested ? hit.normal : vec3(0.0), r)) {
            radiance += throughput * r;
            break;
        }
        normal = hit.normal;
        if (!giUnseenHitDirect(q, normal, hit.brickId, rng, r, albedo, p)) {
            radiance += throughput * giProbeIrradiance(probeIndex, normal);
            break;
        }
        radiance += throughput * r;
        throughput *= albedo;
        float survive = max(throughput.r, max(throughput.g, throughput.b));
        if (survive < 1e-3) break;  // a black surface (a lamp's back)
        if (level >= GI_UNSEEN_ROULETTE) {  // unbiased: a path that goes on carries the light of those that ended
            survive = min(survive, 0.95);
            if (giRandom(rng) >= survive) break;
            throughput /= survive;
        }
    }
    return giFinite(radiance);
}

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
        radiance = giMissRadiance(d);
        kind = GI_TEXEL_MISS;
    } else if (!giRadianceAtSide(ray.origin + d * hit.t, hit.brickId, hit.brickUvw, hit.cascade, hit.alphaTested ? hit.normal : vec3(0.0),
                                 radiance)) {
        vec3 q = ray.origin + d * hit.t;  // a surface no cache holds light for
        bool lit = false;
#ifdef GI_UNSEEN_FROM_VCT
        // The clip-map's voxels hold the light of surfaces the camera never saw (voxelized from the app's draws).
        radiance = blVctSurfaceRadiance(q, d, lit);
        lit = lit && giFinite(radiance);
#endif
        if (!lit) lit = giUnseenHitRadiance(q, hit.normal, hit.brickId, probeIndex, rng, radiance);
        if (!lit) {
            // A surface no view has lit yet, and no light for it here: marked for the projection pass to fill from
            // the probe's known hits. (Keeping a reprojected texel's old value instead biased probes dark: that
            // value may have come through another probe's directions, often a miss.)
            imageStore(probes, texel, vec4(0.0, 0.0, 0.0, GI_TEXEL_UNKNOWN_HIT));
            return;
        }
    }
    vec4 value = vec4(radiance, kind == GI_TEXEL_HIT ? GI_TEXEL_HIT + min(hit.t, 60000.0) : kind);
    if (reprojected && old.a > GI_TEXEL_UNKNOWN_HIT) value.rgb = mix(old.rgb, radiance, GI_PROBE_BLEND);
    imageStore(probes, texel, value);
}

// 16 threads per probe (4 probes per group), one per 2×2 block of texels, one ray each. Every probe, new or
// reprojected, traces one texel of each block a frame (rotating, all four within four frames); a reprojected probe keeps
// the others. A new probe's other texels stay empty until their turn; the projection scales the traced ones up to the
// whole hemisphere. (New probes tracing all 64 texels at once made their SIMD groups trace four rays in series, and
// those groups set the pass's time.)
// With the parallax test (GI_PROBE_PARALLAX) a block where the reprojection marked texels (negative alpha: their hit
// may lie in another direction from here) traces its first marked texel from its turn on instead of its turn, and
// leaves its other marked texels empty, as a new probe's untraced ones: carried by their direction, their light came
// from the wrong places, and the corridor's drifted lower over frames (78 % of the path tracer's at 480 frames against
// 81 % emptied). Tracing every marked texel besides the turns, listed within each group or in a dispatch of their own,
// added about a quarter to the pass's rays and more than half to its time (docs/notes/gi-quality.md); one ray per
// block keeps the pass's cost at the turns'.
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
    uint traced = turn;
    bool found = false;  // a marked texel to trace
    for (uint i = 0u; i < 4u; ++i) {
        uint k = (turn + i) & 3u;
        ivec2 texel = ivec2(tile * 8u + base + uvec2(k & 1u, k >> 1));
        if (!valid || (k != turn && !reprojected)) {
            imageStore(probes, texel, vec4(0.0));  // GI_TEXEL_EMPTY
            continue;
        }
#ifdef GI_PROBE_PARALLAX
        if (!reprojected) continue;
        vec4 v = imageLoad(probes, texel);
        if (v.a >= 0.0) continue;
        if (!found) {
            traced = k;
            found = true;
        } else {
            imageStore(probes, texel, vec4(0.0));  // GI_TEXEL_EMPTY
        }
#endif
    }
    if (!valid) return;
    uvec2 local = base + uvec2(traced & 1u, traced >> 1);
    vec4 old = reprojected ? imageLoad(probes, ivec2(tile * 8u + local)) : vec4(0.0);
    giFillTexel(tile, probeIndex, info, local, reprojected, vec4(old.rgb, abs(old.a)));
}
