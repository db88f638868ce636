#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Hybrid shadows' rays (classify::ShadowClassifier::trace): dispatched indirectly, 32 threads per listed tile and 8
// tiles per group; each pixel of the tile's ray mask traces one ray towards the sun's centre through the distance field
// (bricklight/trace.glsl) over the tile's interval, and the tile's hit-mask texel takes the rays' answers in place
// of the shadow maps' for those pixels. The votes meet in shared memory (no subgroup operations).
layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;
#include "shadow_params.glsl"
#include "bricklight/trace.glsl"  // the field at its default slots: atlas texture 15, read buffers 4..7
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_TEXTURE(1) uniform sampler2D normalTexture;
BL_READ_BUFFER(1) Tiles { uvec4 tiles[]; } list;
BL_READ_BUFFER(2) Counts { uint counts[8]; } count;  // [7]: the listed tiles
BL_IMAGE(0, r32ui) uniform uimage2D hitMask;

shared uint hits[8];

void main() {
    uint slot = gl_LocalInvocationID.x >> 5u, lane = gl_LocalInvocationID.x & 31u;
    uint index = gl_WorkGroupID.x * 8u + slot;
    bool listed = index < count.counts[7];
    uvec4 record = listed ? list.tiles[index] : uvec4(0u);
    ivec2 tile = ivec2(record.x & 0xFFFFu, record.x >> 16u);
    ivec2 pixel = tile * ivec2(8, 4) + ivec2(lane & 7u, lane >> 3u);
    uint bit = 1u << lane;
    if (lane == 0u) hits[slot] = 0u;
    barrier();
    if ((record.y & bit) != 0u) {
        float depth = texelFetch(depthTexture, pixel, 0).r;
        vec3 n = normalize(texelFetch(normalTexture, pixel, 0).xyz * params.normalScale.xyz + params.normalBias.xyz);
        vec3 origin = blShadowWorldPosition(pixel, depth) + n * params.trace.x;
        BlSdfRay ray = blSdfMakeRay(origin, params.sun.xyz, uintBitsToFloat(record.z), uintBitsToFloat(record.w));
        ray.epsilonScale = params.trace.y;
        if (blSdfTrace(ray).hit) atomicOr(hits[slot], bit);
    }
    barrier();
    if (lane == 0u && listed) {
        uint before = imageLoad(hitMask, tile).x;
        imageStore(hitMask, tile, uvec4((before & ~record.y) | hits[slot]));
    }
}
