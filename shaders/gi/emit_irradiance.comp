#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_sh.glsl"
// Pass 13: the probes' SH into the world-space irradiance cache: in every traced cascade, the brick of the
// voxel that holds the probe (a quarter voxel off the surface, on the side it faces) blends the probe in
// with weight 1/(1 + samples), at least 1/16, so the cache follows changes within tens of frames.
// It runs early in the next frame, on the last frame's probes (placed with that frame's camera), beside
// the injection: as the pass after the projection it was a level of its own (128 groups at 1080p) on the
// frame's critical path, and the projection now reads the world cache (which the pixels see one frame
// later than before; the cache moves by at most 1/16 a frame anyway).
layout(local_size_x = 64) in;
BL_CONSTANTS(2) uniform Pass { mat4 inverseViewProjection; } pass;  // of the frame the probes belong to
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
    vec3 p = giWorldPosition(giPixelUv(giProbePixel(info)), uintBitsToFloat(info.y), pass.inverseViewProjection);
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
