#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_sh.glsl"
// Pass 12: each probe's 64 radiance texels into L2 SH. Four probes per group, 16 threads per probe, four
// texels per thread (texel = lane + 16 j): a thread projects its texels (centre direction, solid angle
// 2π/64) and sums them in registers, then a reduction in shared memory over the probe's 16 threads sums
// the lanes. Hits of unknown radiance take the mean of their known neighbours in the probe's map, or of
// the probe's known hits (a first reduction) where no neighbour is known (giUnknownHitStandIn); empty
// texels are left out and the rest scaled up to cover the hemisphere. (One group of 64 threads per probe,
// one texel each, spent its time in the six-step reductions and their barriers.)
// Output per probe: 9 vec4 (rgb coefficient; w of the first = the fraction of texels with data), twice:
// the probe's own SH (`probeSH`, which emit_irradiance.comp blends into the world cache) and the SH the
// pixels read (`probeIrradianceSH`), GI_WORLD_SHARE of which is the world cache at the probe
// (`probeWorldSH`, probe_world_sh.comp) where it has data.
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_TEXTURE(0) uniform sampler2D probes;
BL_STORAGE_BUFFER(0) ProbeSH { vec4 probeSH[]; };
BL_STORAGE_BUFFER(1) ProbeIrradianceSH { vec4 probeIrradianceSH[]; };
BL_READ_BUFFER(2) ProbeWorldSH { vec4 probeWorldSH[]; };
BL_IMAGE(0, r32ui) uniform readonly uimage3D giRadianceCache;
#define GI_USES_RADIANCE_CACHE
#include "gi_bricks.glsl"

// The radiance leaving the probe's own surface (the radiance cache there, finest cascade with data).
bool giSurfaceRadiance(vec3 p, vec3 n, out vec3 radiance) {
    for (uint c = giFrame.cascades.x; c <= giFrame.cascades.y; ++c) {
        uint brick;
        vec3 uvw;
        if (!giBrickAt(p + n * (0.125 * giVoxelSize(c)), c, brick, uvw) && !giBrickAt(p, c, brick, uvw)) continue;
        float w;
        radiance = giSampleRadianceCache(brick, uvw, w);
        if (w > 0.0) return true;
    }
    return false;
}

// [value][thread]: a thread's values lie 65 words apart, so that the writes (neighbouring threads,
// neighbouring words) and the sums (lanes 0..8 of a probe reading rows 3i.. at the same column: rows 195
// words apart, a different bank each) are free of bank conflicts.
const uint kRow = 65u;
shared float partial[28 * kRow];
shared float knownPartial[4 * kRow];  // the first reduction's own rows: no barrier before the second's writes
shared vec4 ownRadiance[4];  // each probe's own surface (giSurfaceRadiance); w 1 where a cache knows it
// Each probe's texels (rgb, alpha the kind): the unknown hits' neighbours, and the projection's input after
// the barrier (read back here rather than kept in registers across it). Packed as the probe image's own
// halves, so exactly; as vec4 (twice the bytes of shared memory) the pass was slower.
shared uvec2 probeTexels[4 * 64];
vec4 giProbeTexel(uint i) {
    uvec2 v = probeTexels[i];
    return vec4(unpackHalf2x16(v.x), unpackHalf2x16(v.y));
}
// The 64 texel centres' directions around +z (giSquareToHemisphere), one computed per thread; each thread
// turns the ones it needs to its probe's normal: one mapping a thread instead of four.
shared vec3 texelDirections[64];

const uint kLanes = 16u;        // threads per probe
const uint kTexelsPerLane = 4u;  // 64 / kLanes

// What a hit of unknown radiance (texel k of the group's probe `slot`) stands for: the mean of the known
// hits among its four neighbours in the probe's 8×8 map (neighbouring directions), else the probe's mean
// of known hits (`hits`: rgb sum, count). The neighbours see the surfaces next to the unknown one — a
// floor hidden behind an object is next to the floor beside it — where the probe's mean also holds what
// lies in other directions (the dark ceiling, seen from a wall). Cornell box, 128²: one bounce 84 → 89 %
// of the reference's mean (relMSE 0.0103 → 0.0096), 64 frames of multi-bounce 0.0309 → 0.0326 (relMSE
// 0.032 → 0.027). The 3×3 window did as well (90 %, 0.0099; 0.0328, 0.027) with more registers; the 5×5
// window worse (multi-bounce 0.0324, 0.028).
vec3 giUnknownHitStandIn(uint slot, uint k, vec4 hits) {
    ivec2 at = ivec2(k % 8u, k / 8u);
    vec4 near = vec4(0.0);
    for (int i = 0; i < 4; ++i) {
        ivec2 q = at + ivec2(i == 0 ? -1 : (i == 1 ? 1 : 0), i == 2 ? -1 : (i == 3 ? 1 : 0));
        if (any(lessThan(q, ivec2(0))) || any(greaterThan(q, ivec2(7)))) continue;
        vec4 v = giProbeTexel(slot * 64u + uint(q.y * 8 + q.x));
        if (v.a > GI_TEXEL_MISS + 0.1) near += vec4(v.rgb, 1.0);
    }
    return near.w > 0.0 ? near.rgb / near.w : hits.rgb / hits.w;
}

void main() {
    uint t = gl_LocalInvocationIndex;
    uint slot = t / kLanes, lane = t % kLanes, first = t - lane;  // probe of the group, lane, lane 0's thread
    uint probeIndex = (gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x) * 4u + slot;
    bool exists = probeIndex < giFrame.tiles.x * giFrame.tiles.y;  // no early return: barriers follow
    uint index = exists ? probeIndex : 0u;
    uvec2 tile = uvec2(index % giFrame.tiles.x, index / giFrame.tiles.x);
    uvec4 info = probeInfo[index];
    vec3 n = giProbeNormal(info);
    bool probeValid = exists && (info.w & GI_PROBE_VALID) != 0u;
    if (lane == 0u) {  // first: the chain of lookups overlaps the reductions instead of following them
        vec3 own = vec3(0.0);
        bool known = probeValid &&
                     giSurfaceRadiance(giWorldPosition(giPixelUv(giProbePixel(info)), uintBitsToFloat(info.y), giCamera.inverseViewProjection), n, own);
        ownRadiance[slot] = vec4(own, known ? 1.0 : 0.0);
    }
    // The world cache at the probe (pass 8b), loaded before the reductions too.
    vec4 world = lane < 9u ? probeWorldSH[index * 9u + lane] : vec4(0.0);
    bool worldKnown = lane < 9u && probeWorldSH[index * 9u].w > 0.0;
    vec4 known = vec4(0.0);  // first reduction: the known hits, which stand in for the hits of unknown radiance
    for (uint j = 0u; j < kTexelsPerLane; ++j) {
        uint k = lane + kLanes * j;
        vec4 r = texelFetch(probes, ivec2(tile * 8u + uvec2(k % 8u, k / 8u)), 0);
        if (!probeValid || !giFinite(r.rgb)) r = vec4(0.0);  // alpha 0: no data
        if (r.a > GI_TEXEL_MISS + 0.1) known += vec4(r.rgb, 1.0);
        probeTexels[slot * 64u + k] = uvec2(packHalf2x16(r.rg), packHalf2x16(r.ba));
    }
    texelDirections[t] = giSquareToHemisphere((vec2(t % 8u, t / 8u) + 0.5) / 8.0);
    // The reductions: one barrier each, after which every thread that needs a sum reads the probe's 16
    // lanes itself (the loads are independent, so they overlap). A tree of four halving steps took a
    // barrier per step, eleven a group in all.
    for (uint k = 0u; k < 4u; ++k) knownPartial[k * kRow + t] = known[k];
    barrier();
    vec4 hits = vec4(0.0);
    for (uint l = 0u; l < kLanes; ++l)
        hits += vec4(knownPartial[first + l], knownPartial[kRow + first + l], knownPartial[2u * kRow + first + l],
                     knownPartial[3u * kRow + first + l]);
    float sh[28];
    for (int i = 0; i < 28; ++i) sh[i] = 0.0;
    vec3 tangent, bitangent;  // the probe's frame (giProbeDirection)
    giBasis(n, tangent, bitangent);
    for (uint j = 0u; j < kTexelsPerLane; ++j) {
        uint k = lane + kLanes * j;
        vec4 r = giProbeTexel(slot * 64u + k);
        if (abs(r.a - GI_TEXEL_UNKNOWN_HIT) < 0.1 && hits.w > 0.0) r = vec4(giUnknownHitStandIn(slot, k, hits), GI_TEXEL_HIT);
        if (r.a <= GI_TEXEL_UNKNOWN_HIT + 0.1) continue;  // empty, or unknown with no known hit to stand in
        float y[9];
        giShBasis(giProbeLocalToWorld(texelDirections[k], n, tangent, bitangent), y);
        for (int i = 0; i < 9; ++i) {
            vec3 c = r.rgb * (y[i] * 2.0 * GI_PI / 64.0);
            sh[3 * i] += c.r;
            sh[3 * i + 1] += c.g;
            sh[3 * i + 2] += c.b;
        }
        sh[27] += 1.0;
    }
    for (uint i = 0u; i < 28u; ++i) partial[i * kRow + t] = sh[i];
    barrier();
    if (exists && lane < 9u) {
        uint i = lane;
        vec4 sum = vec4(0.0);  // coefficient i's rgb and the covered texels
        for (uint l = 0u; l < kLanes; ++l)
            sum += vec4(partial[3u * i * kRow + first + l], partial[(3u * i + 1u) * kRow + first + l],
                        partial[(3u * i + 2u) * kRow + first + l], partial[27u * kRow + first + l]);
        // The lower hemisphere is what a point just off the surface sees below it: the surface itself.
        // Filling it with the surface's own radiance (not zero) makes the SH a whole-sphere estimate, so a
        // pixel or a world-cache brick with another normal reads it correctly; for the probe's own normal
        // it changes nothing (the L2 clamped-cosine kernel integrates to 0 over the lower hemisphere).
        // Its projection is the SH of a constant over the lower hemisphere: c·(√π, 0, -√(3π)/2, 0, ...)
        // rotated to n, i.e. c·Y-weights evaluated analytically below.
        vec4 ownSurface = ownRadiance[slot];
        vec3 self = ownSurface.w > 0.0 ? ownSurface.rgb : (hits.w > 0.0 ? hits.rgb / hits.w : vec3(0.0));
        float covered = sum.w;
        float scale = covered > 0.0 ? 64.0 / covered : 0.0;
        vec3 c = sum.rgb * scale;
        if (covered > 0.0) {
            // ∫ over the lower hemisphere of Y_lm: zonal coefficients (l0: 2π·0.282095, l1: -π·0.488603,
            // l2: 0) along n.
            float yn[9];
            giShBasis(n, yn);
            float zonal = i == 0u ? 2.0 * GI_PI * 0.282095 : (i < 4u ? -GI_PI * 0.488603 * yn[i] / 0.488603 : 0.0);
            c += self * zonal;
        }
        vec4 own = vec4(c, i == 0u ? covered / 64.0 : 0.0);
        probeSH[index * 9u + i] = own;
        if (covered > 0.0 && worldKnown) own.rgb = mix(c, world.rgb, GI_WORLD_SHARE);
        probeIrradianceSH[index * 9u + i] = own;
    }
}
