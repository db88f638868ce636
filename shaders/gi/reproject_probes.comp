#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 7: reuse last frame's probes. One group per new probe: 9 threads score the previous probes of the
// 3×3 tiles around where this probe was last frame (same plane, similar normal, close by), the best one
// wins, and every thread carries one texel over — re-mapped through the directions, since the two probes'
// hemispheres differ, and checked for parallax (below). Texels whose direction the old probe did not cover stay
// empty (alpha 0).
layout(local_size_x = 8, local_size_y = 8) in;
// The largest parallax (sine of the angle) a carried hit may have: about the angular radius of one of the 64
// equal-area texels (2π/64 sr).
#define GI_REPROJECT_PARALLAX 0.18
BL_READ_BUFFER(0) PreviousProbeInfo { uvec4 previousProbeInfo[]; };
BL_STORAGE_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_TEXTURE(0) uniform sampler2D previousProbes;
BL_TEXTURE(1) uniform sampler2D motionNow;
BL_IMAGE(0, rgba16f) uniform writeonly image2D probes;

shared float scores[9];
shared uint candidates[9];

// Where the previous frame's probe `index` (normal m) keeps its texel in world direction d: the probe's 8×8
// square and the texel in it. False where d is below the probe's horizon.
bool giOldTexel(uint index, vec3 m, vec3 d, out ivec2 square, out ivec2 at) {
    vec3 tm, bm;
    giBasis(m, tm, bm);
    vec3 local = vec3(dot(d, tm), dot(d, bm), dot(d, m));
    square = ivec2(index % giFrame.tiles.x, index / giFrame.tiles.x) * 8;
    at = min(ivec2(giHemisphereToSquare(local) * 8.0), ivec2(7));
    return local.z > 0.0;
}

// The nearest hit among the old probe's texel `at` and its 8 neighbours: its distance (1e30 where none holds a hit).
float giNearestHit(ivec2 square, ivec2 at) {
    float nearest = 1e30;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            ivec2 o = at + ivec2(x, y);
            if (any(lessThan(o, ivec2(0))) || any(greaterThan(o, ivec2(7)))) continue;
            float h = texelFetch(previousProbes, square + o, 0).a - GI_TEXEL_HIT;
            if (h > 0.0) nearest = min(nearest, h);
        }
    return nearest;
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
    barrier();
    float best = 0.0;
    uint chosen = 0u;
    for (uint i = 0u; i < 9u; ++i)
        if (scores[i] > best) {
            best = scores[i];
            chosen = candidates[i];
        }
    ivec2 texel = ivec2(tile * 8u + gl_LocalInvocationID.xy);
    vec4 value = vec4(0.0);
    if (best > 0.0) {
        uvec4 old = previousProbeInfo[chosen];
        vec3 d = giProbeDirection(n, (vec2(gl_LocalInvocationID.xy) + 0.5) / 8.0);
        vec3 m = giProbeNormal(old);
        vec3 q = giWorldPosition(giPixelUv(giProbePixel(old)), uintBitsToFloat(old.y), giCamera.previousInverseViewProjection);
        ivec2 square, at;
        if (giOldTexel(chosen, m, d, square, at)) {
            value = texelFetch(previousProbes, square + at, 0);
            // Parallax: the old probe saw its hits from elsewhere (up to 16 pixel footprints away: meters along a wall
            // seen at a grazing angle), and from here a hit may lie in another direction: its light belongs to another
            // texel. The texel is marked (negative alpha) for fill_probes to trace again this frame where the nearest
            // hit among it and its neighbours lies off d by more than about a texel's angular radius: a surface the
            // old probe saw just beside d may stand in front of the texel's own hit from here (testing the texel's
            // own hit alone kept far hits that a near object hides from the new probe: a box's colour bleeding on
            // the floor fell from 0.67 to 0.56 of the path tracer's). Carried without the test, the corridor's walls,
            // lit from far down the corridor at grazing angles, took their light from probes meters nearer to or
            // farther from the light, and the error compounded over frames: its indirect light was 89 % of the path
            // tracer's at 120 frames and 68 % at 480 (docs/notes/gi-quality.md).
            if (giHasFlag(GI_FLAG_PROBE_PARALLAX)) {
                float nearest = giNearestHit(square, at);
                if (nearest < 1e30 && giParallax(q + d * nearest - p, d) > GI_REPROJECT_PARALLAX) value.a = -value.a;
            }
        }
    }
    imageStore(probes, texel, value);
    if (t == 0u && valid) probeInfo[index].w = (info.w & ~GI_PROBE_REPROJECTED) | (best > 0.0 ? GI_PROBE_REPROJECTED : 0u);
}
