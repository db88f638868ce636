#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_sh.glsl"
// Pass 5: spread the brick SH irradiance cache into neighbouring bricks of one cascade (time-sliced: the
// finest cascade every other frame, the next every fourth, ...). A brick takes the mean of its six face
// neighbours that have data and that it can see: the segment between the two voxel centres must not cross
// a surface (sphere-traced through the field), so light does not propagate through walls. Bricks with no
// samples of their own take the mean (weight 0.5); observed ones move towards it by 1/(8·(1 + weight)).
layout(local_size_x = 64) in;
BL_CONSTANTS(2) uniform Pass { uvec4 cascade; } pass;  // x: the cascade of this frame
BL_READ_BUFFER(0) BrickOwners { uint brickOwners[]; };
BL_STORAGE_BUFFER(0) BrickSH { uvec2 giBrickSH[]; };
#define GI_USES_BRICK_SH
#include "gi_bricks.glsl"

bool giSegmentClear(vec3 a, vec3 b, uint cascade) {
    float len = length(b - a);
    vec3 d = (b - a) / len;
    float voxel = giVoxelSize(cascade);
    float threshold = 0.6 * voxel / 7.0;
    float t = 0.0;
    for (int i = 0; i < 24 && t < len; ++i) {
        float dist = blSdfDistance(a + d * t, cascade);
        if (dist < 0.0) dist = voxel;  // outside or unbuilt: nothing known, step on
        if (dist < threshold) return false;
        t += max(dist, threshold);
    }
    return true;
}

void main() {
    uint brick = gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x;
    if (brick >= giFrame.cascades.w) return;
    uint owner = brickOwners[brick];
    if (owner == BL_SDF_NO_OWNER || (owner >> 24) != pass.cascade.x) return;
    uint cascade;
    ivec3 voxel = giOwnerVoxel(owner, cascade);
    if (giBrickOfVoxel(voxel, cascade) != brick) return;  // freed (its voxel holds another brick or none)
    float voxelSize = giVoxelSize(cascade);
    vec3 centre = (vec3(voxel) + 0.5) * voxelSize;
    float selfWeight;
    GiSH self = giLoadBrickSH(brick, selfWeight);
    GiSH sum = giShZero();
    float count = 0.0;
    for (int f = 0; f < 6; ++f) {
        ivec3 offset = ivec3(0);
        offset[f >> 1] = (f & 1) == 0 ? -1 : 1;
        uint other = giBrickOfVoxel(voxel + offset, cascade);
        if (other == BL_SDF_UNBUILT) continue;
        float w;
        GiSH s = giLoadBrickSH(other, w);
        if (w <= 0.0) continue;
        if (!giSegmentClear(centre, centre + vec3(offset) * voxelSize, cascade)) continue;
        for (int i = 0; i < 9; ++i) sum.c[i] += s.c[i];
        count += 1.0;
    }
    if (count == 0.0) return;
    for (int i = 0; i < 9; ++i) sum.c[i] /= count;
    float t = selfWeight <= 0.0 ? 1.0 : 0.125 / (1.0 + selfWeight);
    GiSH result = giShMix(self, sum, t);
    float weight = selfWeight <= 0.0 ? 0.5 : selfWeight;
    for (int i = 0; i < 9; ++i)
        giBrickSH[brick * 9u + uint(i)] = uvec2(packHalf2x16(result.c[i].rg), packHalf2x16(vec2(result.c[i].b, i == 0 ? weight : 0.0)));
}
