#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 3: forget the cache entries of bricks the SDF freed. Every brick remembers the owner (voxel) its
// cache was written for; where the SDF's owner differs, the brick was freed and reused elsewhere (or
// never written): its 4³ radiance texels and its SH are cleared. A full pass over the brick pool, so it
// also catches bricks freed by several SDF updates between two GI frames.
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) BrickOwners { uint brickOwners[]; };
BL_STORAGE_BUFFER(0) CacheOwners { uint cacheOwners[]; };
BL_STORAGE_BUFFER(1) BrickSH { uvec2 brickSH[]; };
BL_IMAGE(0, r32ui) uniform writeonly uimage3D radianceCache;

void main() {
    uint brick = gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x;
    if (brick >= giFrame.cascades.w) return;
    uint owner = brickOwners[brick];
    if (owner == cacheOwners[brick]) return;
    cacheOwners[brick] = owner;
    for (uint i = 0u; i < 9u; ++i) brickSH[brick * 9u + i] = uvec2(0u);
    uint perAxis = giFrame.cascades.z;
    ivec3 base = ivec3(brick % perAxis, (brick / perAxis) % perAxis, brick / (perAxis * perAxis)) * 4;
    for (int k = 0; k < 64; ++k) imageStore(radianceCache, base + ivec3(k & 3, (k >> 2) & 3, k >> 4), uvec4(0u));
}
