#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#define GI_USES_CHANGED_REGIONS
#include "gi_common.glsl"
#include "gi_alpha.glsl"
// Pass 3: forget the cache entries of bricks the SDF freed, and pick this frame's bricks to re-light.
// Every brick remembers the owner entry (voxel and allocation generation) its cache was written for;
// where the SDF's entry differs, the brick was freed and reallocated — elsewhere, or to the same voxel
// with new geometry (or it was never written): its radiance cache slot is cleared and pushed back on the
// free stack, its SH and its material are cleared. A full pass over the brick pool, so it also catches
// bricks freed by several SDF updates between two GI frames. (Before the owner entries carried the
// generation, a brick handed back to its own voxel by the builder kept its cache, with the light of
// geometry that may have moved away. How often that happens depends on the order of the builder's
// atomics: a full rebuild of the Cornell box gave a few of its 10710 bricks back to their voxels.)
// With relighting on, a brick whose albedo is known, that the camera has not seen for GI_RELIGHT_AFTER
// frames and that is out of view (giBrickInView) — or that it has not seen for GI_RELIGHT_STALE frames —
// is appended, every GI_RELIGHT_PERIOD-th frame, to this frame's relight list: words 0..2 are the
// indirect dispatch's arguments (x = bricks listed, one group each), word 3 counts the candidates, the
// bricks follow. The frames alternate between two lists; this pass also empties the other one (0, 1, 1,
// 0) for the next frame, so that the host uploads nothing per frame.
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) BrickOwners { uint brickOwners[]; };
BL_STORAGE_BUFFER(0) CacheOwners { uint cacheOwners[]; };
BL_STORAGE_BUFFER(1) BrickSH { uvec2 brickSH[]; };
BL_STORAGE_BUFFER(2) BrickMaterial { uint brickMaterial[]; };
BL_STORAGE_BUFFER(3) RelightList { uint relightList[]; };
BL_STORAGE_BUFFER(4) CacheSlots { uint giCacheSlots[]; };
BL_STORAGE_BUFFER(5) FreeSlots { int freeSlotCount; uint freeSlots[]; };
BL_STORAGE_BUFFER(6) NextRelightList { uint nextRelightList[]; };
BL_IMAGE(0, r32ui) uniform writeonly uimage3D radianceCache;
// The application's G-buffer (gi_input.glsl), as the downsample stores it: the two run side by side.
BL_TEXTURE(0) uniform sampler2D inputDepth;
BL_TEXTURE(1) uniform sampler2D inputNormals;
BL_TEXTURE(2) uniform sampler2D inputRoughness;
#include "gi_bricks.glsl"
#include "gi_input.glsl"

// Whether the camera may see the voxel (world coordinates `voxel`, edge `size`): some of its box inside
// the frustum's side planes, and its centre not hidden behind this frame's depth buffer. A brick in view
// is the screen's to update, however long injection happened to miss it (coarse cascades are injected by
// every 2^k-th pixel only): re-lighting such bricks as well made what the camera sees depend on which
// bricks injection happened to miss, and Vulkan and GL drifted apart (docs/gi.md, "Relighting"). In
// doubt (the centre off screen, or on sky), in view.
bool giBrickInView(ivec3 voxel, float size) {
    vec3 lo = vec3(voxel) * size;
    bvec4 allOutside = bvec4(true);  // beyond +x, -x, +y, -y
    bool allBehind = true;
    for (int k = 0; k < 8; ++k) {
        vec4 c = giCamera.viewProjection * vec4(lo + vec3(k & 1, (k >> 1) & 1, k >> 2) * size, 1.0);
        allOutside = bvec4(allOutside.x && c.x > c.w, allOutside.y && c.x < -c.w, allOutside.z && c.y > c.w, allOutside.w && c.y < -c.w);
        allBehind = allBehind && c.w <= 0.0;
    }
    if (allBehind || any(allOutside)) return false;
    vec3 centre = lo + 0.5 * size;
    vec4 c = giCamera.viewProjection * vec4(centre, 1.0);
    if (c.w <= 0.0) return true;
    vec2 uv = c.xy / c.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return true;
    float depth;
    uint surface;
    giReadInput(uvec2(uv * vec2(giFrame.size.xy)), depth, surface);
    if (giIsSky(depth)) return true;
    // Hidden: the visible surface there is nearer than the box's nearest point (half a diagonal, 0.87
    // voxel, from the centre), with half a voxel to spare.
    float visible = length(giWorldPosition(uv, depth, giCamera.inverseViewProjection) - giFrame.camera.xyz);
    return visible > length(centre - giFrame.camera.xyz) - 1.4 * size;
}

void main() {
    uint brick = gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x;
    if (brick == 0u) {
        nextRelightList[0] = 0u;
        nextRelightList[1] = 1u;
        nextRelightList[2] = 1u;
        nextRelightList[3] = 0u;
    }
    if (brick >= giFrame.cascades.w) return;
    uint owner = brickOwners[brick];
    uint m = brick * GI_MATERIAL_WORDS;
    if (owner != cacheOwners[brick]) {
        cacheOwners[brick] = owner;
        for (uint i = 0u; i < 9u; ++i) brickSH[brick * 9u + i] = uvec2(0u);
        for (uint i = 0u; i < GI_MATERIAL_WORDS; ++i) brickMaterial[m + i] = 0u;
        // Cells an alpha pass wrote since the last dispatch (header word 1) already belong to the new owner.
        if (blAlphaCacheKept() && blAlphaCacheWords[1] == 0u)
            for (uint i = 0u; i < 64u; ++i) blAlphaCacheWords[BL_ALPHA_CACHE_HEADER + brick * 64u + i] = 0u;
        uint slot = giCacheSlots[brick];
        giCacheSlots[brick] = GI_SLOT_NONE;
        if (slot < GI_SLOT_PENDING) {
            ivec3 base = giCacheSlotBase(slot);
            for (int k = 0; k < 64; ++k) imageStore(radianceCache, base + ivec3(k & 3, (k >> 2) & 3, k >> 4), uvec4(0u));
            freeSlots[atomicAdd(freeSlotCount, 1)] = slot;
        }
        return;
    }
    if (owner != BL_SDF_NO_OWNER && giFrame.cache.y > 0u) {
        // Where the field's geometry just changed (a mover's old and new place, grown by its reach) the cached
        // light is dropped: it holds the light of the scene before the change (colour bled from the mover
        // where it was, its shadow), which the screen's feedback loop would otherwise carry for many frames.
        // The material stays (the brick's geometry did not change, or its owner would have).
        uint cascade;
        ivec3 voxel = giOwnerVoxel(owner, cascade);
        float size = giVoxelSize(cascade);
        if (giInChangedRegion(vec3(voxel) * size, vec3(voxel + 1) * size, GI_CHANGE_FEEDBACK_FRAMES)) {
            for (uint i = 0u; i < 9u; ++i) brickSH[brick * 9u + i] = uvec2(0u);
            uint slot = giCacheSlots[brick];
            giCacheSlots[brick] = GI_SLOT_NONE;
            if (slot < GI_SLOT_PENDING) {
                ivec3 base = giCacheSlotBase(slot);
                for (int k = 0; k < 64; ++k) imageStore(radianceCache, base + ivec3(k & 3, (k >> 2) & 3, k >> 4), uvec4(0u));
                freeSlots[atomicAdd(freeSlotCount, 1)] = slot;
            }
        }
    }
    if ((giFrame.relight.y & GI_RELIGHT_ALBEDO) == 0u || owner == BL_SDF_NO_OWNER) return;
    uint seen = brickMaterial[m + 2u];
    if (seen == 0u || (brickMaterial[m] >> 24) == 0u) return;  // never seen, or no albedo learnt
    // Coarser cascades are injected by every 2^k-th pixel only (inject_radiance.comp), so a brick there
    // that the camera sees can go unreached for a few frames by chance: it must be unseen for longer.
    uint level = min((owner >> 24) - min(owner >> 24, giFrame.cascades.x), 4u);
    uint unseen = giFrameIndex() + 1u - seen;
    bool whole = unseen >= (GI_RELIGHT_AFTER << level) && (brick + giFrameIndex()) % GI_RELIGHT_PERIOD == 0u;
    // The view test is conservative (in doubt, in view), so a brick it calls visible may still be one the
    // screen never reaches (its centre on sky, behind a thin occluder, ...): after GI_RELIGHT_STALE × 2^k
    // frames without injection it is re-lit all the same, or it would keep stale light for ever.
    if (whole && unseen < (GI_RELIGHT_STALE << level)) {
        uint cascade;
        ivec3 voxel = giOwnerVoxel(owner, cascade);
        whole = !giBrickInView(voxel, giVoxelSize(cascade));
    }
    // A brick holding cards is listed even while in view, every GI_RELIGHT_CARD_PERIOD-th frame, for the cards'
    // sides the camera does not see (GI_RELIGHT_CARD_SIDES, relight_cache.comp).
    bool cardSides = !whole && (brick + giFrameIndex()) % GI_RELIGHT_CARD_PERIOD == 0u && giBrickHoldsCards(brick);
    if (!whole && !cardSides) return;
    // Cards take at most about half the budget (the count read before the add races a little): the other half stays
    // for the bricks whose light may have changed out of view.
    if (cardSides && relightList[3] >= GI_RELIGHT_BUDGET / 2u) return;
    uint slot = atomicAdd(relightList[3], 1u);
    if (slot >= GI_RELIGHT_BUDGET) return;
    relightList[4u + slot] = brick | (whole ? 0u : GI_RELIGHT_CARD_SIDES);
    atomicMax(relightList[0], slot + 1u);
}
