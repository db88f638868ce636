#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The shadow classifier (shadows::ShadowClassifier): 16 threads per 8×4 tile, two pixels a thread, sixteen tiles (4 × 4,
// 32 × 16 pixels) per 256-thread group — a group per tile left the GPU launching groups rather than working.
// Per pixel: off screen, sky or facing away from the sun needs no ray (facing away: shadowed); in Normals mode the
// rest need one; in Cascades mode a blocker search in the first cascade that holds the pixel decides — every tap
// nearer the sun than the receiver: shadowed; none (with rejectLit): lit; a mix: a ray, bounded by the nearest and
// the farthest blocker the taps saw. The tile's masks and interval are reduced through shared memory (never
// subgroup operations: lavapipe's subgroups are 8 wide), then one thread appends the tile to the list
// and writes its hit-mask texel.
layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;

#include "shadow_params.glsl"
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_TEXTURE(1) uniform sampler2D normalTexture;
BL_TEXTURE(2) uniform sampler2D shadowMap;
BL_STORAGE_BUFFER(0) Tiles { uvec4 tiles[]; } list;
// Groups of 8 listed tiles (the trace's dispatchIndirect x), 1, 1, cut-off tiles, ray pixels, cut-off pixels, active pixels,
// listed tiles.
BL_STORAGE_BUFFER(1) Counts { uint counts[8]; } count;
// The counts the next classification adds to (the previous one's): zeroed here, so that no clear, and no barrier
// after it, precede the pass.
BL_STORAGE_BUFFER(2) NextCounts { uint counts[8]; } nextCount;
BL_IMAGE(0, r32ui) uniform writeonly uimage2D hitMask;
BL_IMAGE(1, r32ui) uniform writeonly uimage2D sureMask;  // bit set: the answer is sure (no ray, or a sure ray later)

const float kNoEnd = 3.0e38;  // a ray interval without an end
shared uint rayMask[16], answerMask[16], activeMask[16], minT[16], maxT[16];
// The group's sums: its tiles go to the list and the counts with one global atomic per word and group, not per tile
// (same-address atomics from every tile bounded the pass).
shared uint listIndex[16], groupListed, groupBase, groupRays, groupCutTiles, groupCutPixels, groupActive;

// The blocker search's sunflower spiral over the unit disc: tap k at angle k · 2.39996323 (the golden angle) and
// radius sqrt((k + 0.5) / taps). The directions and sqrt(k + 0.5) are tabled rather than computed per tap and pixel:
// sines, cosines and square roots run on the special-function units, at a quarter of the FMA rate.
const vec2 kSpiral[32] = vec2[32](
    vec2(1.000000000, 0.000000000), vec2(-0.737368878, 0.675490294),
    vec2(0.087425725, -0.996171041), vec2(0.608438860, 0.793600752),
    vec2(-0.984713485, -0.174181951), vec2(0.843755296, -0.536728051),
    vec2(-0.259604306, 0.965715074), vec2(-0.460907023, -0.887448430),
    vec2(0.939321296, 0.343038633), vec2(-0.924345557, 0.381556406),
    vec2(0.423845998, -0.905734271), vec2(0.299283862, 0.954164121),
    vec2(-0.865211208, -0.501407584), vec2(0.976675774, -0.214719426),
    vec2(-0.575129432, 0.818062428), vec2(-0.128510686, -0.991708124),
    vec2(0.764648993, 0.644446986), vec2(-0.999146054, 0.041317822),
    vec2(0.708829418, -0.705379938), vec2(-0.046191451, 0.998932605),
    vec2(-0.640709141, -0.767783691), vec2(0.991069412, 0.133346993),
    vec2(-0.820858340, 0.571131846), vec2(0.219481375, -0.975616690),
    vec2(0.497180869, 0.867646923), vec2(-0.952692775, -0.303934987),
    vec2(0.907791137, -0.419422523), vec2(-0.386061089, 0.922473217),
    vec2(-0.338452272, -0.940983560), vec2(0.885189434, 0.465230767),
    vec2(-0.966970007, 0.254890182), vec2(0.540837745, -0.841126942));
const float kSpiralRoot[32] = float[32](
    0.707106781, 1.224744871, 1.581138830, 1.870828693, 2.121320344, 2.345207880, 2.549509757, 2.738612788,
    2.915475947, 3.082207001, 3.240370349, 3.391164992, 3.535533906, 3.674234614, 3.807886553, 3.937003937,
    4.062019202, 4.183300133, 4.301162634, 4.415880433, 4.527692569, 4.636809248, 4.743416490, 4.847679857,
    4.949747468, 5.049752469, 5.147815070, 5.244044241, 5.338539126, 5.431390246, 5.522680509, 5.612486080);

// One pixel's class: whether it needs a ray (and the ray's interval), the answer without one, whether it faces the sun.
struct PixelClass {
    bool needsRay, answer, isActive;
    float t0, t1;
};
PixelClass classifyPixel(ivec2 pixel) {
    bool onScreen = all(lessThan(uvec2(pixel), params.size.xy));
    float depth = onScreen ? texelFetch(depthTexture, min(pixel, ivec2(params.size.xy) - 1), 0).r : 1.0;
    bool reversed = params.options2.y != 0u;
    bool surface = onScreen && (reversed ? depth > 0.0 : depth < 1.0);  // NaN: sky
    vec3 n = texelFetch(normalTexture, min(pixel, ivec2(params.size.xy) - 1), 0).xyz * params.normalScale.xyz + params.normalBias.xyz;
    bool facing = dot(n, params.sun.xyz) > 0.0;
    bool isActive = surface && facing;
    bool needsRay = isActive, answer = surface && !facing;  // facing away: shadowed, no ray
    float t0 = params.normalBias.w, t1 = kNoEnd;
    bool cascadesMode = (params.size.w & 1u) == 1u && isActive;
    if (cascadesMode) {
        vec3 world = blShadowWorldPosition(pixel, depth);
        uint cascade = params.options.x;
        vec3 s = vec3(0.0);
        for (uint c = 0u; c < params.options.x; ++c) {
            vec3 sc = (params.worldToShadow[c] * vec4(world, 1.0)).xyz;
            vec4 r = params.uvRect[c];
            if (cascade == params.options.x && all(greaterThan(sc.xy, r.xy)) && all(lessThan(sc.xy, r.zw))) {
                cascade = c;
                s = sc;
            }
        }
        answer = false;  // beyond every cascade: lit as far as the maps know (the ray decides)
        if (cascade < params.options.x) {
            mat4 m = params.worldToShadow[cascade];
            vec2 mapSize = vec2(params.options2.zw);
            float range = params.depthRange[cascade];
            // The penumbra a blocker can cast on the receiver grows with its distance: at most the receiver's
            // distance from the depth-0 plane on the sun's side.
            float radiusWorld = params.sun.w * max(s.z, 0.0) * range;
            vec2 texelsPerWorld = vec2(length(vec3(m[0][0], m[1][0], m[2][0])), length(vec3(m[0][1], m[1][1], m[2][1]))) * mapSize;
            vec2 radius = radiusWorld * texelsPerWorld + 1.0;
            vec4 rect = params.uvRect[cascade] * vec4(mapSize, mapSize);
            float receiver = s.z - params.normalScale.w;
            uint taps = params.options.y, valid = 0u, blocking = 0u;
            float nearestSun = 1.0e30, nearestReceiver = -1.0e30;
            float tapScale = inversesqrt(float(taps));  // taps: 8, 16, 24 or 32
            for (uint k = 0u; k < taps; ++k) {
                // A sunflower spiral over the disc: even coverage with a fixed pattern.
                vec2 at = floor(s.xy * mapSize + (kSpiralRoot[k] * tapScale) * kSpiral[k] * radius);
                if (any(lessThan(at, rect.xy)) || any(greaterThanEqual(at, rect.zw))) continue;
                float d = texelFetch(shadowMap, ivec2(at), 0).r;
                ++valid;
                nearestSun = min(nearestSun, d);
                if (d < receiver) {
                    ++blocking;
                    nearestReceiver = max(nearestReceiver, d);
                }
            }
            bool allBlock = valid > 0u && blocking == valid, noneBlock = blocking == 0u;
            needsRay = !allBlock && !(noneBlock && valid > 0u && params.options.z != 0u);
            answer = allBlock || (valid > 0u && 2u * blocking > valid);
            // The ray's interval: from the blocker the taps saw nearest the receiver to the one nearest the sun,
            // widened by the depth offset and a texel, and by the search radius sideways.
            if (params.options.w != 0u && blocking > 0u) {
                float slack = params.normalScale.w * range + 2.0 / max(min(texelsPerWorld.x, texelsPerWorld.y), 1.0e-20);
                t0 = max((s.z - nearestReceiver) * range - slack, params.normalBias.w);
                t1 = (s.z - nearestSun) * range + slack + radiusWorld;
            }
        }
    }
    return PixelClass(needsRay, answer, isActive, t0, t1);
}

void main() {
    uint slot = gl_LocalInvocationID.x >> 4u, lane = gl_LocalInvocationID.x & 15u;
    uvec2 tile = uvec2(gl_WorkGroupID.xy) * uvec2(4u, 4u) + uvec2(slot & 3u, slot >> 2u);
    bool tileOnScreen = all(lessThan(tile, (params.size.xy + uvec2(7u, 3u)) / uvec2(8u, 4u)));
    // Two horizontally adjacent pixels a thread: twice the reads in flight per thread, half the shared atomics.
    uvec2 inTile = uvec2((lane & 3u) * 2u, lane >> 2u);
    ivec2 pixel = ivec2(tile * uvec2(8u, 4u) + inTile);
    uint bit = 1u << (inTile.y * 8u + inTile.x);  // y · 8 + x; the second pixel's is bit << 1
    if (lane == 0u) {
        rayMask[slot] = 0u;
        answerMask[slot] = 0u;
        activeMask[slot] = 0u;
        minT[slot] = floatBitsToUint(kNoEnd);
        maxT[slot] = 0u;
    }
    if (gl_LocalInvocationID.x == 0u) {
        if (gl_WorkGroupID.x == 0u && gl_WorkGroupID.y == 0u)
            for (uint i = 0u; i < 8u; ++i) nextCount.counts[i] = (i == 1u || i == 2u) ? 1u : 0u;  // indirect y, z: 1
        groupListed = 0u;
        groupRays = 0u;
        groupCutTiles = 0u;
        groupCutPixels = 0u;
        groupActive = 0u;
    }
    barrier();

    PixelClass a = classifyPixel(pixel), b = classifyPixel(pixel + ivec2(1, 0));
    uint rays = (a.needsRay ? bit : 0u) | (b.needsRay ? bit << 1u : 0u);
    if (rays != 0u) {
        atomicOr(rayMask[slot], rays);
        // Non-negative floats order as their bits.
        float lo = min(a.needsRay ? max(a.t0, 0.0) : kNoEnd, b.needsRay ? max(b.t0, 0.0) : kNoEnd);
        float hi = max(a.needsRay ? max(a.t1, 0.0) : 0.0, b.needsRay ? max(b.t1, 0.0) : 0.0);
        atomicMin(minT[slot], floatBitsToUint(lo));
        atomicMax(maxT[slot], floatBitsToUint(hi));
    }
    uint answers = (a.answer ? bit : 0u) | (b.answer ? bit << 1u : 0u);
    if (answers != 0u) atomicOr(answerMask[slot], answers);
    uint facingSun = (a.isActive ? bit : 0u) | (b.isActive ? bit << 1u : 0u);
    if (facingSun != 0u) atomicOr(activeMask[slot], facingSun);
    barrier();
    uint tileRays = bitCount(rayMask[slot]);
    bool tileLead = lane == 0u && tileOnScreen;
    bool listTile = tileLead && tileRays > params.options2.x;
    if (tileLead) {
        if (listTile) {
            listIndex[slot] = atomicAdd(groupListed, 1u);
            atomicAdd(groupRays, tileRays);
        } else if (tileRays > 0u) {
            atomicAdd(groupCutTiles, 1u);
            atomicAdd(groupCutPixels, tileRays);
        }
        atomicAdd(groupActive, bitCount(activeMask[slot]));
        imageStore(hitMask, ivec2(tile), uvec4(answerMask[slot]));
        // Every pixel without a ray was decided (sky, facing away, all or no taps blocking); cut-off tiles' ray pixels
        // keep the taps' majority, unsure.
        imageStore(sureMask, ivec2(tile), uvec4(~rayMask[slot]));
    }
    barrier();
    if (gl_LocalInvocationID.x == 0u) {
        if (groupListed > 0u) {
            groupBase = atomicAdd(count.counts[7], groupListed);
            // Groups of 8 listed tiles for the trace: the group that ends the list sets the largest value.
            atomicMax(count.counts[0], (groupBase + groupListed + 7u) / 8u);
            atomicAdd(count.counts[4], groupRays);
        }
        if (groupCutTiles > 0u) {
            atomicAdd(count.counts[3], groupCutTiles);
            atomicAdd(count.counts[5], groupCutPixels);
        }
        if (groupActive > 0u) atomicAdd(count.counts[6], groupActive);
    }
    barrier();
    if (listTile) list.tiles[groupBase + listIndex[slot]] = uvec4(tile.x | (tile.y << 16u), rayMask[slot], minT[slot], maxT[slot]);
}
