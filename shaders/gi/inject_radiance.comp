#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#define GI_USES_CHANGED_REGIONS
#include "gi_common.glsl"
// Pass 4: the previous frame's lit image into the radiance cache. One pixel per GI_INJECT_TILE² tile per frame
// (rotating through the tile), reprojected into last frame's image where the disocclusion mask says it saw
// the same surface, then blended into the cache texel at the surface point (moved half a texel towards
// the side the camera sees, so light stays on its own side of thin walls) in every traced cascade that
// has a brick there. The blend weight follows how often the texel is reached (below).
// With relighting on, the brick also learns the pixel's albedo (and emission), and when it was last seen.
layout(local_size_x = 8, local_size_y = 8) in;
// One pixel of each GI_INJECT_TILE² tile per frame (ContextDesc::injectTile): by default 2, or 4 from an
// internal width of 1440 on (core/gi/gi_constants.h: injectTileFor). The cache's texels are a fixed size
// in the world, so at a higher resolution more pixels reach each of them; the wider tile keeps about as
// many injections per texel and frame as 2×2 tiles at 1080p's internal 960×540, and the pass's cost with
// it (at 4K / 50 % with 2×2 tiles it was the largest pass of its level).
BL_CONSTANTS(2) uniform Pass { uvec4 inject; } pass;  // x: the tile side
#define GI_INJECT_TILE (pass.inject.x)
BL_TEXTURE(0) uniform sampler2D depthNow;
BL_TEXTURE(1) uniform usampler2D surfaceNow;
BL_TEXTURE(2) uniform sampler2D motionNow;
BL_TEXTURE(3) uniform sampler2D disocclusion;
BL_TEXTURE(4) uniform sampler2D previousLit;
BL_TEXTURE(5) uniform sampler2D diffuseAlbedo;  // a black 1×1 without relighting
BL_TEXTURE(6) uniform sampler2D emission;       // a black 1×1 without emission
BL_IMAGE(0, r32ui) uniform coherent uimage3D giRadianceCache;
BL_STORAGE_BUFFER(0) BrickMaterial { uint brickMaterial[]; };
coherent BL_STORAGE_BUFFER(1) CacheSlots { uint giCacheSlots[]; };
BL_STORAGE_BUFFER(2) FreeSlots { int freeSlotCount; uint freeSlots[]; };  // a stack; clear_freed_bricks.comp pushes
#include "gi_bricks.glsl"
#define GI_INJECT_BATCH 8u

// A packed cache texel (slot << 6 | x | y << 2 | z << 4) as image coordinates.
ivec3 giInjectTexel(uint code) {
    return giCacheSlotBase(code >> 6) + ivec3(code & 3u, (code >> 2) & 3u, (code >> 4) & 3u);
}

// The brick's cache slot, popped from the free stack at its first injection. False where there is none:
// the pool is full (the brick stays uncached and retries next frame), or another thread is allocating it
// in this dispatch (this sample is dropped). The last giFrame.cache.x free slots go only to injections
// that carry light: a brick whose first light is black (in the first frames everything not lit directly
// is, since GI starts from nothing) waits for light. Otherwise a small or full cache could be taken by
// dark bricks for good, and GI would stay black (a 32-slot cache on the Cornell box did on a GPU; slots
// return only when the SDF frees their bricks). The count is read before the pop: threads reading it
// together may take a few of the kept slots, but a pop is never undone while other pops succeed.
bool giCacheSlot(uint brick, bool carriesLight, out uint slot) {
    slot = giCacheSlots[brick];
    if (slot == GI_SLOT_PENDING) return false;
    if (slot != GI_SLOT_NONE) return true;
    if (!carriesLight && freeSlotCount <= int(giFrame.cache.x)) return false;
    if (atomicCompSwap(giCacheSlots[brick], GI_SLOT_NONE, GI_SLOT_PENDING) != GI_SLOT_NONE) return false;
    int top = atomicAdd(freeSlotCount, -1);
    if (top <= 0) {  // empty: undo (nothing pushes during this pass, so the count never looks positive wrongly)
        atomicAdd(freeSlotCount, 1);
        atomicExchange(giCacheSlots[brick], GI_SLOT_NONE);
        return false;
    }
    slot = freeSlots[top - 1];
    atomicExchange(giCacheSlots[brick], slot);
    return true;
}

void main() {
    uvec2 tile = gl_GlobalInvocationID.xy;
    uint k = (giFrameIndex() * 7u + giPcg(tile.x * 7919u + tile.y)) % (GI_INJECT_TILE * GI_INJECT_TILE);
    uvec2 pixel = tile * GI_INJECT_TILE + uvec2(k % GI_INJECT_TILE, k / GI_INJECT_TILE);
    if (any(greaterThanEqual(pixel, giFrame.size.xy))) return;
    float depth = texelFetch(depthNow, ivec2(pixel), 0).r;
    if (giIsSky(depth) || texelFetch(disocclusion, ivec2(pixel), 0).r < 0.5) return;
    vec2 uv = giPixelUv(pixel);
    vec3 lit = textureLod(previousLit, uv - texelFetch(motionNow, ivec2(pixel), 0).xy, 0.0).rgb;
    if (!giFinite(lit) || any(lessThan(lit, vec3(0.0)))) return;  // never let a bad input into the cache
    vec3 p = giWorldPosition(uv, depth, giCamera.inverseViewProjection);
    // Where geometry just changed, last frame's image holds the light of before the change (clear_freed_bricks.comp
    // dropped the cache there): nothing is injected until the region is old enough.
    if (giInChangedRegion(p, p, GI_CHANGE_FEEDBACK_FRAMES)) return;
    vec3 n = giSurfaceNormal(texelFetch(surfaceNow, ivec2(pixel), 0).r);
    vec3 toCamera = normalize(giFrame.camera.xyz - p);
    if (dot(n, toCamera) < 0.0) n = -n;
    // The pixel's footprint on the surface (one pixel across, widened by the slant).
    vec3 side = giWorldPosition(uv + vec2(1.0 / float(giFrame.size.x), 0.0), depth, giCamera.inverseViewProjection);
    float footprint = max(length(side - p) / max(dot(n, toCamera), 0.25), 1e-6);
    uint hash = giPcg(tile.x * 7919u + tile.y * 104729u + giFrameIndex());
    bool learn = (giFrame.relight.y & GI_RELIGHT_ALBEDO) != 0u;
    vec3 albedo = vec3(0.0), emitted = vec3(0.0);
    if (learn) {  // only with relighting: the two inputs are black 1×1 stand-ins otherwise
        albedo = textureLod(diffuseAlbedo, uv, 0.0).rgb;
        emitted = textureLod(emission, uv, 0.0).rgb;
        learn = giFinite(albedo) && giFinite(emitted) && all(greaterThanEqual(emitted, vec3(0.0)));
        albedo = clamp(albedo, vec3(0.0), vec3(1.0));
    }
    // The cascades in batches of GI_INJECT_BATCH, each in phases (the bricks, their slots, the texels' old
    // values, the blends): a phase's loads do not depend on each other, so they are in flight together,
    // where one cascade after another waited for three dependent loads each (brick map, slot, texel).
    for (uint c0 = giFrame.cascades.x; c0 <= giFrame.cascades.y; c0 += GI_INJECT_BATCH) {
        uint bricks[GI_INJECT_BATCH], texels[GI_INJECT_BATCH];  // texels: slot << 6 | texel in the slot's 4³
        for (uint k = 0u; k < GI_INJECT_BATCH; ++k) {
            uint c = c0 + k;
            bricks[k] = BL_SDF_UNBUILT;
            // Coarser cascades' texels are reached by many pixels: only every 2^k-th pixel (k = cascade
            // above the start, at most 4) injects there, which the blend weight below accounts for.
            uint level = min(c - giFrame.cascades.x, 4u);
            if (c > giFrame.cascades.y || (hash & ((1u << level) - 1u)) != 0u) continue;
            vec3 uvw;
            // (giBrickAt leaves BL_SDF_UNBUILT where it finds no brick.)
            if (!giBrickAt(p + n * (0.125 * giVoxelSize(c)), c, bricks[k], uvw) && !giBrickAt(p, c, bricks[k], uvw)) continue;
            uvec3 t = uvec3(min(ivec3(uvw * 4.0), ivec3(3)));
            texels[k] = t.x | t.y << 2 | t.z << 4;
        }
        for (uint k = 0u; k < GI_INJECT_BATCH; ++k) {
            uint slot;
            if (bricks[k] == BL_SDF_UNBUILT) continue;
            if (giCacheSlot(bricks[k], any(greaterThan(lit, vec3(0.0))), slot)) texels[k] |= slot << 6;
            else bricks[k] = BL_SDF_UNBUILT;
        }
        uint olds[GI_INJECT_BATCH];
        for (uint k = 0u; k < GI_INJECT_BATCH; ++k)
            olds[k] = bricks[k] == BL_SDF_UNBUILT ? 0u : imageLoad(giRadianceCache, giInjectTexel(texels[k])).r;
        for (uint k = 0u; k < GI_INJECT_BATCH; ++k) {
            if (bricks[k] == BL_SDF_UNBUILT) continue;
            uint c = c0 + k, level = min(c - giFrame.cascades.x, 4u);
            // About this many injections reach the texel per frame (its area over the pixel footprint's, one
            // pixel in GI_INJECT_TILE² injecting): the weight of each is set so that the texel moves ~1/4 of
            // the way to the current light per frame, whatever the resolution and cascade. A texel smaller
            // than a pixel is reached only every few frames and then takes most of the new value (fresh,
            // not stale).
            float texelSize = 0.25 * giVoxelSize(c);
            float perFrame = texelSize * texelSize / (footprint * footprint * float(GI_INJECT_TILE * GI_INJECT_TILE << level));
            float alpha = clamp(0.25 / perFrame, 1.0 / 256.0, 0.9);
            vec3 value = olds[k] == 0u ? lit : mix(blDecodeRgb9e5(olds[k]), lit, alpha);
            imageStore(giRadianceCache, giInjectTexel(texels[k]), uvec4(blEncodeRgb9e5(value)));
            if (learn) {
                // The brick's material: a running mean over one in four of the pixels that reach it (racing
                // writers lose an update now and then, which a mean can afford): every pixel writing the
                // same two words serializes their same-address stores. Every pixel still marks the brick seen
                // (relighting's view test).
                uint m = bricks[k] * GI_MATERIAL_WORDS;
                if ((hash >> 8 & 3u) == 0u) {
                    vec4 known = unpackUnorm4x8(brickMaterial[m]);
                    brickMaterial[m] = packUnorm4x8(vec4(known.a > 0.5 ? mix(known.rgb, albedo, 0.125) : albedo, 1.0));
                    if ((giFrame.relight.y & GI_RELIGHT_EMISSION) != 0u) {
                        uint e = brickMaterial[m + 1u];
                        brickMaterial[m + 1u] = blEncodeRgb9e5(e != 0u ? mix(blDecodeRgb9e5(e), emitted, 0.125) : emitted);
                    }
                }
                brickMaterial[m + 2u] = giFrameIndex() + 1u;
            }
        }
    }
}
