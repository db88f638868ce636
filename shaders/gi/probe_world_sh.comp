#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_sh.glsl"  // gi_bricks.glsl's brick SH reads use GiSH
// Pass 8b: the world cache at each probe: its SH, trilinear over the bricks around the probe (a quarter
// voxel off the surface, in the finest traced cascade that has any; gi_bricks.glsl), for the
// projection to blend GI_WORLD_SHARE of into the SH the pixels read. It needs only the probes' places and
// the brick SH after propagation, so it runs beside the probe fill instead of adding to a level of its
// own; reading the world cache once per probe instead of at every pixel took three quarters of the
// interpolation away (eight brick lookups and 72 loads a pixel).
// Output per probe: 9 vec4 (rgb coefficient; w of the first = the lookup's total weight, 0: no data).
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_READ_BUFFER(1) BrickSH { uvec2 giBrickSH[]; };
BL_STORAGE_BUFFER(0) ProbeWorldSH { vec4 probeWorldSH[]; };
#define GI_USES_BRICK_SH
#include "gi_bricks.glsl"

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= giFrame.tiles.x * giFrame.tiles.y) return;
    uvec4 info = probeInfo[index];
    uint bricks[8];
    float weights[8];
    float total = 0.0;
    if ((info.w & GI_PROBE_VALID) != 0u) {
        vec3 p = giWorldPosition(giPixelUv(giProbePixel(info)), uintBitsToFloat(info.y), giCamera.inverseViewProjection);
        total = giWorldCacheCorners(p, giProbeNormal(info), bricks, weights);
    }
    for (int i = 0; i < 9; ++i) {
        vec3 c = total > 0.0 ? giWorldCacheCoefficient(bricks, weights, total, i) : vec3(0.0);
        probeWorldSH[index * 9u + uint(i)] = vec4(c, i == 0 ? total : 0.0);
    }
}
