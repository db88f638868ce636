// Mover grids (docs/sdf.md, *Mover grids*): a rigid dynamic instance's distances come from a grid of its
// mesh's nearest triangles, built once per mesh and scale, instead of from its triangles re-voxelized.
// Mirrors core/sdf/sdf_layout.h. The including shader declares `moverGridTable` (uvec4[]) and
// `moverGridData` (uint[]).
//
// moverGridData: per grid, its mesh's triangles in object space (3 vec4 each, as the triangle scratch), then
// per level ℓ (one per cascade, spacing = cascade ℓ's brixel / scale) one key per lattice point:
// (quantized distance << 20) | triangle, for the nearest triangle within BL_SDF_MOVER_REACH_CELLS cells of
// the point, else BL_SDF_MOVER_NO_KEY. A sample p of the instance is then the exact distance to the nearest of
// the (up to 8) keys' triangles around p: exact wherever p's nearest triangle is nearest to one of the 8
// points, and a real triangle's distance (never below the true one) everywhere.
//
// moverGridTable, per mover (this round's index): rows 0-2 the world-to-object transform (3x4, float bits),
// row 3 (scale, material tag, first triangle's vec4 index / 3, first level row); per grid level two rows:
// (lattice origin xyz in object space, 1 / spacing) as float bits, (dims xyz, first key's word).
// In the triangle scratch a mover's reference chunk is v0 = (first voxel xyz, cascade), v1 = (last voxel
// xyz, BL_SDF_MOVER_TAG + mover index), v2 = (0, 0, 0, material tag).
#ifndef BRICKLIGHT_SDF_MOVER_GRID_GLSL
#define BRICKLIGHT_SDF_MOVER_GRID_GLSL

#define BL_SDF_MOVER_TAG 2.0
#define BL_SDF_MOVER_NO_KEY 0xFFFFFFFFu
#define BL_SDF_MOVER_TRIANGLE_BITS 20u
#define BL_SDF_MOVER_TRIANGLE_MASK 0xFFFFFu
// Keys cover distances up to the band plus a cell's diagonal: every lattice point around a sample within the
// band of the mesh has one.
#define BL_SDF_MOVER_REACH_CELLS (BL_SDF_BAND_BRIXELS + 1.7320509)

#ifdef BL_SDF_MOVER_SAMPLING
vec3 blSdfMoverTriangleVertex(uint word) {
    return uintBitsToFloat(uvec3(moverGridData[word], moverGridData[word + 1u], moverGridData[word + 2u]));
}

// Squared world distance from world point p to mover m's mesh at cascade `level`, at most cap2.
float blSdfMoverDistanceSq(uint m, uint level, vec3 p, float cap2) {
    uvec4 info = moverGridTable[4u * m + 3u];
    vec4 h = vec4(p, 1.0);
    vec3 q = vec3(dot(uintBitsToFloat(moverGridTable[4u * m]), h), dot(uintBitsToFloat(moverGridTable[4u * m + 1u]), h),
                  dot(uintBitsToFloat(moverGridTable[4u * m + 2u]), h));
    float scale = uintBitsToFloat(info.x);
    uvec4 l0 = moverGridTable[info.w + 2u * level], l1 = moverGridTable[info.w + 2u * level + 1u];
    vec3 g = (q - uintBitsToFloat(l0.xyz)) * uintBitsToFloat(l0.w);
    ivec3 dims = ivec3(l1.xyz);
    // Outside the lattice: farther than the band from the mesh's bounds.
    if (any(lessThan(g, vec3(0.0))) || any(greaterThan(g, vec3(dims - 1)))) return cap2;
    ivec3 i0 = clamp(ivec3(round(g)), ivec3(1), dims - 2) - 1;
    float best = cap2 / (scale * scale);
    uint last = BL_SDF_MOVER_NO_KEY;
    for (int corner = 0; corner < 27; ++corner) {
        ivec3 i = i0 + ivec3(corner % 3, (corner / 3) % 3, corner / 9);
        uint key = moverGridData[l1.w + uint((i.z * dims.y + i.y) * dims.x + i.x)];
        if (key == BL_SDF_MOVER_NO_KEY) continue;
        uint t = key & BL_SDF_MOVER_TRIANGLE_MASK;
        if (t == last) continue;
        last = t;
        uint at = 12u * (info.z + t);
        best = min(best, blPointTriangleDistanceSq(q, blSdfMoverTriangleVertex(at), blSdfMoverTriangleVertex(at + 4u),
                                                   blSdfMoverTriangleVertex(at + 8u)));
    }
    return best * scale * scale;
}
#endif

#endif
