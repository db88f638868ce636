#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
// Copies one level's toroidally opposite columns and slices into its border columns (x) and slices (z) in every
// region of the atlas, so that filtered reads at a level's edge wrap (vct_layout.glsl). Per region four faces:
// the columns x = −1 and x = resolution (every slice, the corners too), then the slices z = −1 and z = resolution
// (the columns in between).
layout(local_size_x = 32, local_size_y = 2, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Level {
    uvec4 params;  // x: the resolution, y: the level, z: the regions
} level;
BL_IMAGE(0, r32ui) uniform uimage3D atlas;

void main() {
    int r = int(level.params.x);
    ivec3 id = ivec3(gl_GlobalInvocationID);  // x: along the face (−1 .. r), y: y, z: region × 4 + face
    uint region = uint(id.z) >> 2u;
    int face = id.z & 3;
    int a = id.x - 1;
    if (a > r || id.y >= r || region >= level.params.z) return;
    ivec3 inner;  // within the level: x, z in −1 .. r
    if (face < 2) inner = ivec3(face == 0 ? -1 : r, id.y, a);
    else {
        if (a < 0 || a >= r) return;  // the corners belong to the column faces
        inner = ivec3(a, id.y, face == 2 ? -1 : r);
    }
    ivec3 source = ivec3((inner.x + r) % r, inner.y, (inner.z + r) % r);
    ivec3 base = ivec3(vctRegionX(region, uint(r)) + 1, 0, int(level.params.y) * (r + 2) + 1);
    imageStore(atlas, base + inner, imageLoad(atlas, base + source));
}
