#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 7: reuse last frame's probes. One group per new probe: 9 threads score the previous probes of the
// 3×3 tiles around where this probe was last frame (same plane, similar normal, close by), the best one
// wins, and its texels are carried over: each old hit to the texel that looks at it from here (below), or without
// the parallax test (ContextFlags::NoProbeParallax) each texel from the old probe's texel of the same direction.
// Texels whose direction the old probe did not cover stay empty (alpha 0).
layout(local_size_x = 8, local_size_y = 8) in;
#define GI_SPLAT_NONE 0xFFFFFFFFu  // no old texel landed in this new texel (the shared arrays below)
// The largest parallax (sine of the angle) a texel no old hit landed in may have when carried by its direction: about
// the angular radius of one of the 64 equal-area texels (2π/64 sr).
#define GI_REPROJECT_PARALLAX 0.18
BL_READ_BUFFER(0) PreviousProbeInfo { uvec4 previousProbeInfo[]; };
BL_STORAGE_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_TEXTURE(0) uniform sampler2D previousProbes;
BL_TEXTURE(1) uniform sampler2D motionNow;
BL_IMAGE(0, rgba16f) uniform writeonly image2D probes;

shared float scores[9];
shared uint candidates[9];
shared uint splat[64];   // per new texel: the key (giSplatKey) of the old texel whose centre landed in it
shared uint spread[64];  // per new texel nothing landed in: the key of the old texel whose patch covers its centre

// Where the previous frame's probe (normal m) keeps its texel in world direction d: the texel in its 8×8 square.
// False where d is below the probe's horizon.
bool giOldTexel(vec3 m, vec3 d, out ivec2 at) {
    vec3 tm, bm;
    giBasis(m, tm, bm);
    vec3 local = vec3(dot(d, tm), dot(d, bm), dot(d, m));
    at = min(ivec2(giHemisphereToSquare(local) * 8.0), ivec2(7));
    return local.z > 0.0;
}

// The nearest hit among an old probe's texel (at `texel` in the previous probes' image) and its 8 neighbours in its
// square: its distance (1e30 where none holds a hit).
float giNearestHit(ivec2 texel) {
    ivec2 square = texel & ~7;
    float nearest = 1e30;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 o = texel + ivec2(x, y);
            if (any(notEqual(o & ~7, square))) continue;
            float h = texelFetch(previousProbes, o, 0).a - GI_TEXEL_HIT;
            if (h > 0.0) nearest = min(nearest, h);
        }
    return nearest;
}

// The splat's key for old texel `from` whose centre lands at `at` (new-texel units) in new texel `to`, the smallest
// winning: how far from the texel's centre it lands, then the old texel.
uint giSplatKey(vec2 at, ivec2 to, uint from) {
    vec2 off = at - (vec2(to) + 0.5);
    return uint(min(dot(off, off), 4.0) * 65535.0) << 6 | from;
}

// Sine of the angle between the unit direction d and the vector v (1 for a zero v).
float giParallax(vec3 v, vec3 d) {
    float len = length(v);
    return len > 0.0 ? length(cross(v / len, d)) : 1.0;
}

void main() {
    uvec2 tile = gl_WorkGroupID.xy;
    uint t = gl_LocalInvocationIndex;
    uint index = tile.y * giFrame.tiles.x + tile.x;
    uvec4 info = probeInfo[index];
    bool valid = (info.w & GI_PROBE_VALID) != 0u;
    vec3 p = vec3(0.0), n = vec3(0.0, 0.0, 1.0);
    if (valid) {
        uvec2 pixel = giProbePixel(info);
        p = giWorldPosition(giPixelUv(pixel), uintBitsToFloat(info.y), giCamera.inverseViewProjection);
        n = giProbeNormal(info);
    }
    if (t < 9u) {
        scores[t] = 0.0;
        candidates[t] = 0u;
        if (valid && giHasFlag(GI_FLAG_HISTORY_VALID) && !giHasFlag(GI_FLAG_RESET_HISTORY)) {
            uvec2 pixel = giProbePixel(info);
            vec2 previousUv = giPixelUv(pixel) - texelFetch(motionNow, ivec2(pixel), 0).xy;
            ivec2 previousTile = ivec2(floor(previousUv * vec2(giFrame.size.xy) / float(giProbeTile()))) +
                                 ivec2(int(t % 3u) - 1, int(t / 3u) - 1);
            if (all(greaterThanEqual(previousTile, ivec2(0))) && all(lessThan(previousTile, ivec2(giFrame.tiles.xy)))) {
                uint c = uint(previousTile.y) * giFrame.tiles.x + uint(previousTile.x);
                uvec4 old = previousProbeInfo[c];
                if ((old.w & GI_PROBE_VALID) != 0u) {
                    vec3 q = giWorldPosition(giPixelUv(giProbePixel(old)), uintBitsToFloat(old.y), giCamera.previousInverseViewProjection);
                    vec3 m = giProbeNormal(old);
                    float distance = length(p - giFrame.camera.xyz);
                    float plane = abs(dot(q - p, n)) / (0.02 * distance);
                    float near = length(q - p) / (16.0 * 2.0 * distance / float(giFrame.size.y));
                    float facing = dot(n, m);
                    if (plane < 1.0 && near < 1.0 && facing > 0.8) {
                        scores[t] = (1.0 - plane) * (1.0 - near) * facing + 1e-3;
                        candidates[t] = c;
                    }
                }
            }
        }
    }
    splat[t] = GI_SPLAT_NONE;
    spread[t] = GI_SPLAT_NONE;
    barrier();
    float best = 0.0;
    uint chosen = 0u;
    for (uint i = 0u; i < 9u; ++i)
        if (scores[i] > best) {
            best = scores[i];
            chosen = candidates[i];
        }
    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    ivec2 texel = ivec2(tile * 8u) + local;
    vec4 value = vec4(0.0);
    bool parallax = giHasFlag(GI_FLAG_PROBE_PARALLAX);
    vec3 m = vec3(0.0, 0.0, 1.0), q = vec3(0.0);
    ivec2 square = ivec2(0);
    if (best > 0.0) {
        uvec4 old = previousProbeInfo[chosen];
        m = giProbeNormal(old);
        q = giWorldPosition(giPixelUv(giProbePixel(old)), uintBitsToFloat(old.y), giCamera.previousInverseViewProjection);
        square = ivec2(chosen % giFrame.tiles.x, chosen / giFrame.tiles.x) * 8;
    }
    // Parallax: the old probe saw its hits from elsewhere (up to 16 pixel footprints away: meters along a wall seen
    // at a grazing angle), so from here a hit lies in another direction, and its light belongs to another texel.
    // Each old texel's hit (its centre's direction at the hit's distance; misses and unknown hits keep their
    // direction) lands in the new texel that looks at it from here; where several land in one, the one landing
    // closest to its centre wins. No preference for the nearer hit: at the resolution of 64 texels a silhouette's
    // texels hold both surfaces, and preferring hits over misses, or near hits over far ones, brightened the
    // Cornell box by 4-10 % (docs/notes/gi-quality.md). Carried by direction without any test, the corridor's walls,
    // lit from far down the corridor at grazing angles, took their light from probes meters nearer to or farther
    // from the light, and the error compounded over frames: its indirect light was 89 % of the path tracer's at 120
    // frames and 68 % at 480. Marking every texel whose hit moved for tracing again fixed that at the price of
    // tracing about a third of the carried texels each frame with a moving camera; moving the hits instead leaves to
    // trace only the texels nothing lands in (below).
    // The old texel's centre and the patch of surface it saw, as seen from here (the texel's corners at the hit's
    // distance), in new-texel units.
    vec2 at = vec2(-1.0), lo = vec2(0.0), hi = vec2(-1.0);
    if (best > 0.0 && parallax) {
        vec4 v = texelFetch(previousProbes, square + local, 0);
        if (v.a > GI_TEXEL_UNKNOWN_HIT - 0.1) {
            vec3 tn, bn;
            giBasis(n, tn, bn);
            float h = v.a - GI_TEXEL_HIT;
            vec3 w = giProbeDirection(m, (vec2(local) + 0.5) / 8.0);
            if (v.a >= GI_TEXEL_HIT) w = q + w * h - p;
            vec3 l = vec3(dot(w, tn), dot(w, bn), dot(w, n));
            if (l.z > 0.0) {
                at = giHemisphereToSquare(normalize(l)) * 8.0;
                ivec2 to = min(ivec2(at), ivec2(7));
                atomicMin(splat[to.y * 8 + to.x], giSplatKey(at, to, t));
                if (v.a >= GI_TEXEL_HIT) {
                    lo = at;
                    hi = at;
                    for (uint k = 0u; k < 4u; ++k) {
                        vec3 c = q + giProbeDirection(m, (vec2(local) + vec2(k & 1u, k >> 1)) / 8.0) * h - p;
                        vec3 lc = vec3(dot(c, tn), dot(c, bn), dot(c, n));
                        if (lc.z <= 0.0) continue;
                        vec2 sc = giHemisphereToSquare(normalize(lc)) * 8.0;
                        lo = min(lo, sc);
                        hi = max(hi, sc);
                    }
                }
            }
        }
    }
    barrier();
    // Texels no centre landed in take the patch that covers their centre (up to a texel from the patch's centre),
    // the closest again: from a probe nearer to a surface its patches spread over more texels than there were.
    if (hi.x >= lo.x) {
        ivec2 to = min(ivec2(at), ivec2(7));
        ivec2 first = clamp(ivec2(ceil(lo - 0.5)), max(to - 1, ivec2(0)), to);
        ivec2 last = clamp(ivec2(floor(hi - 0.5)), to, min(to + 1, ivec2(7)));
        for (int y = first.y; y <= last.y; ++y)
            for (int x = first.x; x <= last.x; ++x)
                if (splat[y * 8 + x] == GI_SPLAT_NONE) atomicMin(spread[y * 8 + x], giSplatKey(at, ivec2(x, y), t));
    }
    barrier();
    if (best > 0.0) {
        vec3 d = giProbeDirection(n, (vec2(local) + 0.5) / 8.0);
        ivec2 same;  // the old probe's texel of direction d
        bool covered = giOldTexel(m, d, same);
        if (!parallax) {
            if (covered) value = texelFetch(previousProbes, square + same, 0);
        } else if (min(splat[t], spread[t]) != GI_SPLAT_NONE) {
            uint s = min(splat[t], spread[t]);
            uint from = s & 63u;
            value = texelFetch(previousProbes, square + ivec2(from % 8u, from / 8u), 0);
            if (value.a >= GI_TEXEL_HIT)  // its distance from here
                value.a = GI_TEXEL_HIT + min(length(q + giProbeDirection(m, (vec2(from % 8u, from / 8u) + 0.5) / 8.0) * (value.a - GI_TEXEL_HIT) - p), 60000.0);
        } else if (covered) {
            // No old hit landed here: the old probe's texel of the same direction, as without the test, unless a hit
            // near that direction lies off it from here by more than about a texel's angular radius (then marked: the
            // fill traces one marked texel of each 2×2 block this frame instead of the block's turn, and empties the
            // others).
            value = texelFetch(previousProbes, square + same, 0);
            float nearest = giNearestHit(square + same);
            if (nearest < 1e30 && giParallax(q + d * nearest - p, d) > GI_REPROJECT_PARALLAX) value.a = -value.a;
        }
    }
    imageStore(probes, texel, value);
    if (t == 0u && valid) probeInfo[index].w = (info.w & ~GI_PROBE_REPROJECTED) | (best > 0.0 ? GI_PROBE_REPROJECTED : 0u);
}
