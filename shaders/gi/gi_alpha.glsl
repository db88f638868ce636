// The alpha (coverage) cache beside the radiance cache (ContextFlags::AlphaCache, docs/gi.md "Foliage"):
// per brick 4³ cells, each counting the alpha-tested surface the app's alpha pass (bricklight/alpha_pass.glsl)
// rasterized there and the share of it the alpha test kept. Rays of the GI go on past hits that the field
// reports as alpha-tested (BlSdfHit::alphaTested) with the probability that the surface is not there, so the
// light they bring back is right on average: cards neither trap the rays (built as solid) nor vanish from
// the occlusion (left out). Bound at storage buffer 7 of every pass that traces; clear_freed_bricks.comp
// forgets the cells of reallocated bricks.
#ifndef BRICKLIGHT_GI_ALPHA_GLSL
#define BRICKLIGHT_GI_ALPHA_GLSL

// A storage buffer even where only read (readonly blocks are read buffers, whose slots the traces have used up).
BL_STORAGE_BUFFER(7) GiAlphaCache { uint giAlphaCache[]; };
#define GI_ALPHA_HEADER 4u  // [0]: 1 when the context keeps the cache (a 16-byte stand-in otherwise)
// Re-traces a ray may start past transparent hits before its next hit counts as opaque whatever the cache
// says: each is a full trace from the hit on, and a ray through a dense field of cards meets many.
#define GI_ALPHA_MAX_CONTINUES 6u

bool giAlphaCacheKept() { return giAlphaCache[0] != 0u; }

// Coverage at brick-local position uvw: the counts of the 2×2×2 cells nearest the point, summed (a card
// through the corner of a cell leaves few fragments in it). -1 where none holds any (no alpha pass there yet).
float giAlphaCoverage(uint brick, vec3 uvw) {
    ivec3 base = clamp(ivec3(floor(uvw * 4.0 - 0.5)), ivec3(0), ivec3(2));
    uint covered = 0u, total = 0u;
    for (int k = 0; k < 8; ++k) {
        ivec3 c = base + ivec3(k & 1, (k >> 1) & 1, k >> 2);
        uint word = giAlphaCache[GI_ALPHA_HEADER + brick * 64u + uint((c.z * 4 + c.y) * 4 + c.x)];
        covered += (word >> 12) & 0xFFFu;
        total += word & 0xFFFu;
    }
    return total == 0u ? -1.0 : float(covered) / float(total);
}

// Whether a hit is a cut-out part of a card this time: only for hits the field calls alpha-tested, with the
// cache's coverage there; unknown coverage counts as opaque (as the field alone would have it).
bool giAlphaTransparent(BlSdfHit hit, inout uint rng) {
    if (!hit.hit || !hit.alphaTested || !giAlphaCacheKept()) return false;
    float coverage = giAlphaCoverage(hit.brickId, hit.brickUvw);
    return coverage >= 0.0 && giRandom(rng) >= coverage;
}

// blSdfTrace that goes on past transparent hits (at most GI_ALPHA_MAX_CONTINUES times).
BlSdfHit giTraceThroughAlpha(BlSdfRay ray, inout uint rng) {
    BlSdfHit hit = blSdfTrace(ray);
    for (uint k = 0u; k < GI_ALPHA_MAX_CONTINUES && giAlphaTransparent(hit, rng); ++k) {
        uint iterations = hit.iterations;
        ray = blSdfContinueRay(ray, hit);
        hit = blSdfTrace(ray);
        hit.iterations += iterations;
    }
    return hit;
}

#endif
