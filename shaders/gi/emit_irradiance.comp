#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_sh.glsl"
// Pass 13: the probes' SH into the world-space irradiance cache: in every traced cascade, the brick of the
// voxel that holds the probe (a quarter voxel off the surface, on the side it faces) blends the probe in
// with weight 1/(1 + samples), at least 1/16, so the cache follows changes within tens of frames.
// It is recorded after the interpolation (the last reader of the cache this frame), beside the blur: as
// the pass right after the projection it was a level of its own (128 groups at 1080p) on the frame's
// critical path. (Emitting last frame's probes early in the next frame instead left the GI further from
// the still renderer after motion stopped: the dynamic test's bound of 0.008 failed three times as often.)
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_READ_BUFFER(1) ProbeSH { vec4 probeSH[]; };
BL_STORAGE_BUFFER(0) BrickSH { uvec2 giBrickSH[]; };
#define GI_USES_BRICK_SH
#include "gi_bricks.glsl"

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= giFrame.tiles.x * giFrame.tiles.y) return;
    uvec4 info = probeInfo[index];
    if ((info.w & GI_PROBE_VALID) == 0u) return;
    float covered = probeSH[index * 9u].w;
    if (covered < 0.5) return;  // too few texels with data to stand for the hemisphere
    GiSH probe;
    for (int i = 0; i < 9; ++i) probe.c[i] = probeSH[index * 9u + uint(i)].rgb;
    vec3 p = giWorldPosition(giPixelUv(giProbePixel(info)), uintBitsToFloat(info.y), giCamera.inverseViewProjection);
    vec3 n = giProbeNormal(info);
    for (uint c = giFrame.cascades.x; c <= giFrame.cascades.y; ++c) {
        uint brick;
        vec3 uvw;
        if (!giBrickAt(p + n * (0.25 * giVoxelSize(c)), c, brick, uvw) && !giBrickAt(p, c, brick, uvw)) continue;
        float weight;
        GiSH old = giLoadBrickSH(brick, weight);
        float alpha = max(1.0 / (1.0 + weight), 1.0 / 16.0);
        GiSH result = giShMix(old, probe, alpha);
        float w = min(weight + 1.0, 16.0);
        for (int i = 0; i < 9; ++i)
            giBrickSH[brick * 9u + uint(i)] = uvec2(packHalf2x16(result.c[i].rg), packHalf2x16(vec2(result.c[i].b, i == 0 ? w : 0.0)));
    }
}
