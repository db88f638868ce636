// Reading the GI's alpha (coverage) cache (gi::ContextFlags::AlphaCache, docs/gi.md "Foliage") from any shader
// that traces the distance field: the coverage of alpha-tested surfaces at a hit that BlSdfHit::alphaTested
// flags. Bind gi::GiContext::alphaCacheBuffer() as a storage buffer at BL_ALPHA_CACHE_SLOT (default 7). Include
// after bricklight/trace.glsl.
#ifndef BRICKLIGHT_ALPHA_CACHE_GLSL
#define BRICKLIGHT_ALPHA_CACHE_GLSL

#ifndef BL_ALPHA_CACHE_SLOT
#define BL_ALPHA_CACHE_SLOT 7
#endif
#define BL_ALPHA_CACHE_HEADER 4u  // [0]: 1 when the context keeps the cache (a 16-byte stand-in otherwise); [1]: 1 from
                                  // an alpha pass to the next dispatch; [2]: rays that met their tracer's bound on
                                  // cards passed (blAlphaCacheCountBoundReached); [3]: unused

// A storage buffer even where only read (readonly blocks are read buffers, whose slots the traces use up).
BL_STORAGE_BUFFER(BL_ALPHA_CACHE_SLOT) BlAlphaCacheBlock { uint blAlphaCacheWords[]; };

bool blAlphaCacheKept() { return blAlphaCacheWords[0] != 0u; }

// Coverage at brick-local position uvw (BlSdfHit::brickUvw): the share of the alpha-tested surface the alpha pass
// found present, over the 2×2×2 cells nearest the point (a card through the corner of a cell leaves few fragments
// in it). -1 where none holds any count (no alpha pass reached it yet).
float blAlphaCacheCoverage(uint brick, vec3 uvw) {
    ivec3 base = clamp(ivec3(floor(uvw * 4.0 - 0.5)), ivec3(0), ivec3(2));
    uint covered = 0u, total = 0u;
    for (int k = 0; k < 8; ++k) {
        ivec3 c = base + ivec3(k & 1, (k >> 1) & 1, k >> 2);
        uint word = blAlphaCacheWords[BL_ALPHA_CACHE_HEADER + brick * 64u + uint((c.z * 4 + c.y) * 4 + c.x)];
        covered += word >> 16;
        total += word & 0xFFFFu;
    }
    return total == 0u ? -1.0 : float(covered) / float(total);
}

// Whether a hit is a cut-out part of a card for a ray with uniform random number u in [0, 1): only hits the field
// flags, with the cache's coverage there; unknown coverage counts as opaque (as the field alone has it).
bool blAlphaCacheTransparent(BlSdfHit hit, float u) {
    if (!hit.hit || !hit.alphaTested || !blAlphaCacheKept()) return false;
    float coverage = blAlphaCacheCoverage(hit.brickId, hit.brickUvw);
    return coverage >= 0.0 && u >= coverage;
}

// A tracer that bounds how many cards a ray may pass (the GI's rays: 6) counts each ray whose next alpha-tested hit
// it then takes as opaque without asking the cache: gi::GiContext::raysAtAlphaBound() reports them. Bind the cache
// with rhi::Access::Atomic to call this.
void blAlphaCacheCountBoundReached() { atomicAdd(blAlphaCacheWords[2], 1u); }

#endif
