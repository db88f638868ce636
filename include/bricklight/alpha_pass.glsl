// The fragment shader of the GI's alpha pass (gi::GiContext::alphaPassState, docs/gi.md "Foliage"). An
// application with alpha-tested geometry writes one of a few lines and compiles it with bricklight_add_shaders:
//
//     #version 450
//     #extension GL_GOOGLE_include_directive : require
//     #include "bricklight/alpha_pass.glsl"
//     bool blAlphaPresent(BlAlphaFragment f) { return /* the material's alpha test at f.user's texture coordinates */; }
//
// It may read the application's own resources: constants slots 0–3, textures 0–14, read buffers 0–3, storage
// buffers 0–6, images 0–7 (read buffers 4–7, texture 15 and storage buffer 7 are ours).
//
// Each triangle is rasterized once per cascade of the distance field, projected along its dominant axis, at
// BL_ALPHA_PIXELS_PER_CELL pixels per side of a cache cell (a 4³ cell of a brick). Every fragment that lands in
// a brick flagged alpha-tested (sdf::InstanceDesc::alphaTested) counts once in its cell, and once more as
// covered where blAlphaPresent says the surface is there: the cell's coverage is the share of the alpha-tested
// surface in it that the alpha test keeps. The projection sees every layer — cards hidden behind others, cards
// the camera never saw — in one pass, with no randomness: the counts are the same every time the pass runs.
// A cell word holds the covered count (high 16 bits) and the total (low 16 bits); the context clears the cells
// when a frame's first alpha pass state is taken. (A compare-and-swap that kept a pass tag in the word instead
// of the clear made the pass many times slower: every fragment of a cell contends for its word.)
#ifndef BRICKLIGHT_ALPHA_PASS_GLSL
#define BRICKLIGHT_ALPHA_PASS_GLSL

#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"

#define BL_ALPHA_PIXELS_PER_CELL 2
#define BL_ALPHA_CACHE_HEADER 4u  // words before the cells: [0] 1 when the context keeps the cache

#ifndef BL_ALPHA_PASS_GEOMETRY
BL_STORAGE_BUFFER(7) BlAlphaCache { uint blAlphaCache[]; };

layout(location = 0) in vec4 blAlphaUser;
layout(location = 1) in vec3 blAlphaWorld;
layout(location = 2) flat in uint blAlphaCascade;

struct BlAlphaFragment {
    vec3 position;  // world space, on the triangle
    vec4 user;      // blAlphaVertex's vector, interpolated
};

// The application's alpha test: whether the surface is there at this fragment.
bool blAlphaPresent(BlAlphaFragment f);

void main() {
    uint cascade = blAlphaCascade;
    BlSdfCascade info = blSdfTable.cascades[cascade];
    vec3 local = blAlphaWorld * info.voxelSize.y - vec3(info.origin.xyz);
    if (any(lessThan(local, vec3(0.0))) || any(greaterThanEqual(local, vec3(64.0)))) return;
    ivec3 voxel = ivec3(floor(local));
    uint brick = blSdfBrickMaps[cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(info.origin.xyz + voxel)];
    if (brick >= BL_SDF_FIRST_STATE) return;
    uint aabb = blSdfBrickAabbs[brick];
    if (aabb == BL_SDF_AABB_NONE || (aabb & BL_SDF_AABB_ALPHA_TESTED) == 0u) return;
    uint index = BL_ALPHA_CACHE_HEADER + brick * 64u + blSdfBrickCell(local - vec3(voxel));
    BlAlphaFragment f;
    f.position = blAlphaWorld;
    f.user = blAlphaUser;
    uint covered = blAlphaPresent(f) ? 1u : 0u;
    // Near saturation the cell's share is known well enough; more would carry the total into the covered count.
    if ((blAlphaCache[index] & 0xFFFFu) >= 0xFF00u) return;
    atomicAdd(blAlphaCache[index], (covered << 16) | 1u);
}
#endif

#endif
