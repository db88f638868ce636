// The pixels the resolve could not fill from the sparse samples (VXGI's refinement): resolve_diffuse.comp lists them,
// refine_diffuse.comp traces their cones, one to an invocation, and resolve_refined.comp sums each pixel's and blends
// it with the history. Traced in the resolve, one pixel's cones one after another, they were the pass's tail: few
// pixels (0.02 % of the atrium's), but the pass ended when their lanes did.
//
// The counts (8 words): the refine pass's dispatchIndirect arguments (groups of 64 cones, 1, 1), the blend pass's
// (groups of 64 pixels, 1, 1), the pixels listed (more than the list holds where it overflowed), one spare.
const uint REFINE_LISTED = 6u;

// Pixels the cone results hold room for this frame (the parameters' spare word: cone results in all).
uint refineCapacity() { return uint(trace.specular.z) / diffuseConeCount(); }

uint packRefinePixel(ivec2 pixel) { return uint(pixel.x) | (uint(pixel.y) << 16u); }
ivec2 unpackRefinePixel(uint word) { return ivec2(word & 0xFFFFu, word >> 16u); }
