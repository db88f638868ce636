#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 7: reuse last frame's probes. One group per new probe: 9 threads score the previous probes of the
// 3×3 tiles around where this probe was last frame (same plane, similar normal, close by), the best one
// wins, and every thread carries one texel over — re-mapped through the directions, since the two probes'
// hemispheres differ. Texels whose direction the old probe did not cover stay empty (alpha 0).
layout(local_size_x = 8, local_size_y = 8) in;
BL_READ_BUFFER(0) PreviousProbeInfo { uvec4 previousProbeInfo[]; };
BL_STORAGE_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_TEXTURE(0) uniform sampler2D previousProbes;
BL_TEXTURE(1) uniform sampler2D motionNow;
BL_IMAGE(0, rgba16f) uniform writeonly image2D probes;

shared float scores[9];
shared uint candidates[9];

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
        vec3 tm, bm;
        giBasis(m, tm, bm);
        vec3 local = vec3(dot(d, tm), dot(d, bm), dot(d, m));
        if (local.z > 0.0) {
            ivec2 oldTexel = ivec2(chosen % giFrame.tiles.x, chosen / giFrame.tiles.x) * 8 +
                             min(ivec2(giHemisphereToSquare(local) * 8.0), ivec2(7));
            value = texelFetch(previousProbes, oldTexel, 0);
        }
    }
    imageStore(probes, texel, value);
    if (t == 0u && valid) probeInfo[index].w = (info.w & ~GI_PROBE_REPROJECTED) | (best > 0.0 ? GI_PROBE_REPROJECTED : 0u);
}
