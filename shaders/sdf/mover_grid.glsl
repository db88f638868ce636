// Mover grids (docs/sdf.md, *Mover grids*): a rigid dynamic instance's distances come from a grid of its
// mesh's nearest triangles, built once per mesh and scale, instead of from its triangles re-voxelized.
// Mirrors core/sdf/sdf_layout.h. The including shader declares `moverGridTable` (uvec4[]) and
// `moverGridData` (uint[]).
//
// moverGridData: per grid, its mesh's triangles in object space (3 vec4 each, as the triangle scratch), then
// per level ℓ (one per cascade, spacing = cascade ℓ's brixel / scale) one key per lattice point:
// (quantized distance << 20) | triangle, for the nearest triangle within BL_SDF_MOVER_REACH_CELLS cells of
// the point, else BL_SDF_MOVER_NO_KEY. A sample p of the instance is then the exact distance to the nearest of
// the triangles of the 27 lattice points around p: exact wherever p's nearest triangle is nearest to one of
// them, and a real triangle's distance (never below the true one) everywhere.
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
// Keys cover distances up to the band plus a voxel's half diagonal (7 cells × 0.866) plus a cell's (the lattice
// point nearest to a voxel's centre is up to that far from it): every lattice point around a sample within the
// band has one, and the point nearest to a voxel's centre tells whether the mover reaches the voxel at all
// (count_references.comp).
#define BL_SDF_MOVER_REACH_CELLS (BL_SDF_BAND_BRIXELS + 7.0)

#ifdef BL_SDF_MOVER_SAMPLING
// A world point in mover m's grid at cascade `level`: its object-space position, lattice coordinate and the
// level's rows.
struct BlSdfMoverPoint {
    vec3 q;       // object space
    vec3 g;       // lattice units (0 .. dims - 1 on the lattice)
    ivec3 dims;
    uvec4 level;  // the level's second row: dims, first key's word
    float cellsToObject;
    float scale;  // object to world distances
    uint firstTriangle;
};

BlSdfMoverPoint blSdfMoverLocate(uint m, uint level, vec3 p) {
    BlSdfMoverPoint r;
    uvec4 info = moverGridTable[4u * m + 3u];
    vec4 h = vec4(p, 1.0);
    r.q = vec3(dot(uintBitsToFloat(moverGridTable[4u * m]), h), dot(uintBitsToFloat(moverGridTable[4u * m + 1u]), h),
               dot(uintBitsToFloat(moverGridTable[4u * m + 2u]), h));
    uvec4 l0 = moverGridTable[info.w + 2u * level];
    r.level = moverGridTable[info.w + 2u * level + 1u];
    float inv = uintBitsToFloat(l0.w);
    r.g = (r.q - uintBitsToFloat(l0.xyz)) * inv;
    r.dims = ivec3(r.level.xyz);
    r.cellsToObject = 1.0 / inv;
    r.scale = uintBitsToFloat(info.x);
    r.firstTriangle = info.z;
    return r;
}

uint blSdfMoverKey(BlSdfMoverPoint r, ivec3 i) { return moverGridData[r.level.w + uint((i.z * r.dims.y + i.y) * r.dims.x + i.x)]; }

// A key's distance (object units, rounded down to its 12-bit step); BL_SDF_MOVER_NO_KEY: the reach.
float blSdfMoverKeyDistance(BlSdfMoverPoint r, uint key) {
    float cells = key == BL_SDF_MOVER_NO_KEY ? BL_SDF_MOVER_REACH_CELLS : float(key >> BL_SDF_MOVER_TRIANGLE_BITS) * BL_SDF_MOVER_REACH_CELLS / 4095.0;
    return cells * r.cellsToObject;
}

// A lower bound of the world distance from p to mover m's mesh at cascade `level`, from the key of the lattice
// point nearest to p alone (distances are 1-Lipschitz: d(p) >= d(point) - |p - point|). No key: the point is
// farther than the reach. Off the lattice: the lattice's edge is as near as p can be.
float blSdfMoverLowerBound(uint m, uint level, vec3 p) {
    BlSdfMoverPoint r = blSdfMoverLocate(m, level, p);
    ivec3 centre = ivec3(round(clamp(r.g, vec3(0.0), vec3(r.dims - 1))));
    float lower = blSdfMoverKeyDistance(r, blSdfMoverKey(r, centre)) - length(r.g - vec3(centre)) * r.cellsToObject;
    return max(lower, 0.0) * r.scale;
}

vec3 blSdfMoverTriangleVertex(uint word) {
    return uintBitsToFloat(uvec3(moverGridData[word], moverGridData[word + 1u], moverGridData[word + 2u]));
}

// Squared world distance from world point p to mover m's mesh at cascade `level`, at most cap2. The lattice
// point nearest to p first, then the other 26 around it; a key whose point is farther from its triangle than
// the best so far plus the point's distance to p cannot give a nearer triangle (triangle inequality) and is
// skipped before its triangle is read. Most samples of a footprint are far from the surface: the nearest
// point's key alone says so.
float blSdfMoverDistanceSq(uint m, uint level, vec3 p, float cap2) {
    BlSdfMoverPoint r = blSdfMoverLocate(m, level, p);
    // Outside the lattice: farther than the band from the mesh's bounds.
    if (any(lessThan(r.g, vec3(0.0))) || any(greaterThan(r.g, vec3(r.dims - 1)))) return cap2;
    ivec3 centre = clamp(ivec3(round(r.g)), ivec3(1), r.dims - 2);
    // The nearest point without a key: it is farther than the reach, p farther than the band. With one, p is at
    // least its distance less |p − point| away (1-Lipschitz): most samples of a footprint end here.
    uint key = blSdfMoverKey(r, centre);
    if (key == BL_SDF_MOVER_NO_KEY) return cap2;
    float best = cap2 / (r.scale * r.scale);
    float nearest = blSdfMoverKeyDistance(r, key) - length(r.g - vec3(centre)) * r.cellsToObject;
    if (nearest > 0.0 && nearest * nearest >= best) return cap2;
    uint last = BL_SDF_MOVER_NO_KEY;
    for (int k = 0; k < 27; ++k) {
        // k = 0 is the centre (offset slot 13); slot 13 of k takes the offset (-1, -1, -1) of slot 0.
        int o = k == 0 ? 13 : (k == 13 ? 0 : k);
        ivec3 i = centre + ivec3(o % 3, (o / 3) % 3, o / 9) - 1;
        if (k > 0) key = blSdfMoverKey(r, i);
        if (key == BL_SDF_MOVER_NO_KEY) continue;
        float lower = blSdfMoverKeyDistance(r, key) - length(r.g - vec3(i)) * r.cellsToObject;
        if (lower > 0.0 && lower * lower >= best) continue;
        uint t = key & BL_SDF_MOVER_TRIANGLE_MASK;
        if (t == last) continue;
        last = t;
        uint at = 12u * (r.firstTriangle + t);
        best = min(best, blPointTriangleDistanceSq(r.q, blSdfMoverTriangleVertex(at), blSdfMoverTriangleVertex(at + 4u),
                                                   blSdfMoverTriangleVertex(at + 8u)));
    }
    return best * r.scale * r.scale;
}
#endif

#endif
