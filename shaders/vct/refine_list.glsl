// The pixels the resolve could not fill from the sparse samples (VXGI's refinement): resolve_diffuse.comp lists them,
// and refine_diffuse.comp traces their cones, one to an invocation, sums each pixel's and blends it with the history.
// Traced in the resolve, one pixel's cones one after another, they were the pass's tail: few pixels (0.02 % of the
// atrium's), but the pass ended when their lanes did.
//
// The counts (8 words): the refine pass's dispatchIndirect arguments (groups, 1, 1), three spare words, the pixels
// listed (more than the list holds where it overflowed), one spare.
const uint REFINE_LISTED = 6u;
const uint REFINE_GROUP = 64u;  // invocations of a refine group: whole pixels of diffuseConeCount() (at most 32) each

// Pixels the list holds room for this frame (the parameters' spare word: refinement entries, a pixel's cones each).
uint refineCapacity() { return uint(trace.specular.z) / diffuseConeCount(); }
uint refinePixelsPerGroup() { return REFINE_GROUP / diffuseConeCount(); }

uint packRefinePixel(ivec2 pixel) { return uint(pixel.x) | (uint(pixel.y) << 16u); }
ivec2 unpackRefinePixel(uint word) { return ivec2(word & 0xFFFFu, word >> 16u); }
