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
// The largest parallax (sine of the angle) a carried texel may have: about the angular radius of one of the 64
// equal-area texels (2π/64 sr).
#define GI_REPROJECT_PARALLAX 0.18
BL_READ_BUFFER(0) PreviousProbeInfo { uvec4 previousProbeInfo[]; };
BL_STORAGE_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_TEXTURE(0) uniform sampler2D previousProbes;
BL_TEXTURE(1) uniform sampler2D motionNow;
BL_IMAGE(0, rgba16f) uniform writeonly image2D probes;

shared float scores[9];
shared uint candidates[9];

// Texel of the previous frame's probe `index` (normal m) in world direction d; empty where d is below its horizon.
vec4 giOldTexel(uint index, vec3 m, vec3 d) {
    vec3 tm, bm;
    giBasis(m, tm, bm);
    vec3 local = vec3(dot(d, tm), dot(d, bm), dot(d, m));
    if (local.z <= 0.0) return vec4(0.0);
    ivec2 at = ivec2(index % giFrame.tiles.x, index / giFrame.tiles.x) * 8 + min(ivec2(giHemisphereToSquare(local) * 8.0), ivec2(7));
    return texelFetch(previousProbes, at, 0);
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
        value = giOldTexel(chosen, m, d);
        // Parallax: the old probe saw its hit from elsewhere (up to 16 pixel footprints away, meters along a wall seen
        // at a grazing angle), and seen from here that point may lie in another direction: its light belongs to
        // another texel. Where it lies off d by more than about a texel's angular radius, the old texel that looks at
        // the point this probe would see along d (about as far away) is tried instead; where that one's hit is off
        // too, the texel is an unknown hit, which the projection fills from its neighbouring directions (leaving it
        // empty scaled the kept texels up to the whole hemisphere, and those are mostly the far hits, whose parallax
        // is small: two-rooms' sunlit room read 123 % instead of 113 %). Carrying the light without this test, the
        // corridor's walls, lit from far down the corridor at grazing angles, got their texels from probes meters
        // nearer or farther from the light: its indirect light was 85 % of the path tracer's at 120 frames and
        // drifted to 65 % by 480 (docs/notes/gi-quality.md).
        float hitDistance = value.a - GI_TEXEL_HIT;
        if (hitDistance > 0.0 && giParallax(q + d * hitDistance - p, d) > GI_REPROJECT_PARALLAX) {
            vec3 aimed = normalize(p + d * hitDistance - q);
            value = giOldTexel(chosen, m, aimed);
            float aimedDistance = value.a - GI_TEXEL_HIT;
            if (!(aimedDistance > 0.0 && giParallax(q + aimed * aimedDistance - p, d) <= GI_REPROJECT_PARALLAX))
                value = vec4(0.0, 0.0, 0.0, GI_TEXEL_UNKNOWN_HIT);
        }
    }
    imageStore(probes, texel, value);
    if (t == 0u && valid) probeInfo[index].w = (info.w & ~GI_PROBE_REPROJECTED) | (best > 0.0 ? GI_PROBE_REPROJECTED : 0u);
}
