// The GI's rays through foliage (ContextFlags::AlphaCache, docs/gi.md "Foliage"): they go on past hits that the
// field reports as alpha-tested (BlSdfHit::alphaTested) with the probability that the surface is not there
// (bricklight/alpha_cache.glsl), so the light they bring back is right on average: cards neither trap the rays
// (built as solid) nor vanish from the occlusion (left out). The cache is bound at storage buffer 7 of every pass
// that traces; clear_freed_bricks.comp forgets the cells of reallocated bricks.
#ifndef BRICKLIGHT_GI_ALPHA_GLSL
#define BRICKLIGHT_GI_ALPHA_GLSL

#include "bricklight/alpha_cache.glsl"

// Re-traces a ray may start past transparent hits before its next hit counts as opaque whatever the cache
// says: each is a full trace from the hit on, and a ray through a dense field of cards meets many.
#define GI_ALPHA_MAX_CONTINUES 6u

// Whether the field flagged the brick as holding alpha-tested surfaces (BL_SDF_AABB_ALPHA_TESTED).
bool giBrickHoldsCards(uint brick) {
    uint aabb = blSdfBrickAabbs[brick];
    return aabb != BL_SDF_AABB_NONE && (aabb & BL_SDF_AABB_ALPHA_TESTED) != 0u;
}

// blSdfTrace that goes on past transparent hits (at most GI_ALPHA_MAX_CONTINUES times; a ray whose next hit
// is alpha-tested once they are spent is counted, blAlphaCacheCountBoundReached).
BlSdfHit giTraceThroughAlpha(BlSdfRay ray, inout uint rng) {
    BlSdfHit hit = blSdfTrace(ray);
    uint k = 0u;
    for (; k < GI_ALPHA_MAX_CONTINUES && blAlphaCacheTransparent(hit, giRandom(rng)); ++k) {
        uint iterations = hit.iterations;
        ray = blSdfContinueRay(ray, hit);
        hit = blSdfTrace(ray);
        hit.iterations += iterations;
    }
    if (k == GI_ALPHA_MAX_CONTINUES && hit.hit && hit.alphaTested) blAlphaCacheCountBoundReached();
    return hit;
}

#endif
