// Brick lookups in the SDF's cascades (the tables of bricklight/trace.glsl), and the per-brick caches:
// the radiance cache (4³ RGB9E5 texels per cache slot in a 3D R32_UINT image, `giRadianceCache`, declared by
// the including pass when GI_USES_RADIANCE_CACHE is defined; a brick has a slot once light was injected
// into it, `giCacheSlots`) and the brick SH irradiance cache (9 × uvec2 per brick: half RGB + half weight
// in coefficient 0, `giBrickSH`, when GI_USES_BRICK_SH is defined).
#ifndef BRICKLIGHT_GI_BRICKS_GLSL
#define BRICKLIGHT_GI_BRICKS_GLSL

float giVoxelSize(uint cascade) { return blSdfTable.cascades[cascade].voxelSize.x; }

// Brick of the voxel that holds p in `cascade` (and p's position in it, [0,1]³); false where the cascade
// does not reach, the voxel is empty or not built.
bool giBrickAt(vec3 p, uint cascade, out uint brick, out vec3 uvw) {
    BlSdfCascade info = blSdfTable.cascades[cascade];
    brick = BL_SDF_UNBUILT;
    uvw = vec3(0.0);
    if (info.origin.w == 0) return false;
    vec3 local = p * info.voxelSize.y - vec3(info.origin.xyz);
    if (any(lessThan(local, vec3(0.0))) || any(greaterThanEqual(local, vec3(64.0)))) return false;
    ivec3 cell = ivec3(floor(local));
    uint state = blSdfBrickMaps[cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(info.origin.xyz + cell)];
    if (state >= BL_SDF_FIRST_STATE) return false;
    brick = state;
    uvw = local - vec3(cell);
    return true;
}

// Brick of a world voxel (integer coordinates) in `cascade`, or BL_SDF_UNBUILT.
uint giBrickOfVoxel(ivec3 voxel, uint cascade) {
    BlSdfCascade info = blSdfTable.cascades[cascade];
    if (info.origin.w == 0) return BL_SDF_UNBUILT;
    ivec3 l = voxel - info.origin.xyz;
    if (any(lessThan(l, ivec3(0))) || any(greaterThanEqual(l, ivec3(64)))) return BL_SDF_UNBUILT;
    uint state = blSdfBrickMaps[cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(voxel)];
    return state >= BL_SDF_FIRST_STATE ? BL_SDF_UNBUILT : state;
}

// World voxel of a brick from its owner entry (cascade << 24 | generation << 18 | physical index,
// bricklight/sdf_layout.glsl): the cascade's window holds exactly one world voxel with that physical index.
ivec3 giOwnerVoxel(uint owner, out uint cascade) {
    cascade = owner >> 24;
    uint physical = owner & BL_SDF_OWNER_VOXEL_MASK;
    ivec3 p = ivec3(physical % 64u, (physical / 64u) % 64u, physical / 4096u);
    ivec3 origin = blSdfTable.cascades[cascade].origin.xyz;
    return origin + ((p - origin) & ivec3(63));
}

// How far a ray starts off the surface at p: the frame's push-off, or (0) half a voxel of the finest
// traced cascade that holds p, which clears the hit epsilon (0.09 voxel) and the distance band.
float giPushOff(vec3 p, float requested) {
    if (requested > 0.0) return requested;
    for (uint c = giFrame.cascades.x; c <= giFrame.cascades.y; ++c) {
        BlSdfCascade info = blSdfTable.cascades[c];
        vec3 local = p * info.voxelSize.y - vec3(info.origin.xyz);
        if (info.origin.w != 0 && all(greaterThanEqual(local, vec3(1.0))) && all(lessThan(local, vec3(63.0))))
            return 0.5 * info.voxelSize.x;
    }
    return 0.5 * blSdfTable.cascades[giFrame.cascades.y].voxelSize.x;
}

#ifdef GI_USES_RADIANCE_CACHE
// Read-only by default; passes that allocate or free slots declare it themselves (GI_CACHE_SLOTS_DECLARED).
#ifndef GI_CACHE_SLOTS_DECLARED
BL_READ_BUFFER(3) CacheSlots { uint giCacheSlots[]; };
#endif

// Radiance at brick-local uvw: trilinear over the brick's written texels (unwritten ones carry no weight). With
// `side` (a unit normal; zero for none), only the texels whose centre lies on that side of the surface through uvw:
// a thin card's two sides share texels, and injection writes the side the camera sees (gi_alpha.glsl).
vec3 giSampleRadianceCacheSide(uint brick, vec3 uvw, vec3 side, out float weight) {
    weight = 0.0;
    uint slot = giCacheSlots[brick];
    if (slot >= GI_SLOT_PENDING) return vec3(0.0);
    ivec3 base = giCacheSlotBase(slot);
    vec3 q = clamp(uvw * 4.0 - 0.5, vec3(0.0), vec3(3.0));
    ivec3 i0 = min(ivec3(floor(q)), ivec3(2));
    vec3 f = q - vec3(i0);
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 8; ++k) {
        ivec3 o = ivec3(k & 1, (k >> 1) & 1, k >> 2);
        if (dot((vec3(i0 + o) + 0.5) * 0.25 - uvw, side) < 0.0) continue;
        uint v = imageLoad(giRadianceCache, base + i0 + o).r;
        if (v == 0u) continue;
        vec3 w3 = mix(1.0 - f, f, vec3(o));
        float w = w3.x * w3.y * w3.z + 1e-4;
        sum += blDecodeRgb9e5(v) * w;
        weight += w;
    }
    return weight > 0.0 ? sum / weight : vec3(0.0);
}
vec3 giSampleRadianceCache(uint brick, vec3 uvw, out float weight) { return giSampleRadianceCacheSide(brick, uvw, vec3(0.0), weight); }

// Radiance leaving the surface at p (found by a ray in `cascade`): the hit brick's cache, else the finest
// other cascade with data there. Finer cascades come first: a ray that coarsened (giMakeRay) hits in a
// coarse cascade, whose bricks the screen injects only every 2^k-th pixel, while the finer bricks around
// the same surface may hold fresher light (or be the only ones with a cache slot when the pool is full).
// Coarser cascades are not read for a hit in the first traced cascade (a ray that has not coarsened yet) where the
// frame lights unseen hits itself (GI_RELIGHT_UNSEEN_HITS): a coarser texel spans more than the hit's, and where the
// hit's own cascade has no light (a surface no view has lit) it holds other surfaces' light — the seen floor's shade
// for a sunlit floor behind the camera, which kept the atrium's shaded pillars at 0.35–0.7 of the path tracer's one
// bounce; lit where it was met (fill_probes_body.glsl) is better. Farther hits keep the fallback: lighting all of
// them where they were met made the probes' fill several times dearer (docs/notes/gi-quality.md).
bool giRadianceAtSide(vec3 p, uint brick, vec3 uvw, uint cascade, vec3 side, out vec3 radiance) {
    float w;
    radiance = giSampleRadianceCacheSide(brick, uvw, side, w);
    if (w > 0.0) return true;
    bool nearUnseenLit = (giFrame.relight.y & GI_RELIGHT_UNSEEN_HITS) != 0u && cascade == giFrame.cascades.x;
    uint last = nearUnseenLit ? cascade : giFrame.cascades.y + 1u;
    for (uint c = giFrame.cascades.x; c < last; ++c) {
        if (c == cascade) continue;
        uint b;
        vec3 u;
        if (!giBrickAt(p, c, b, u)) continue;
        radiance = giSampleRadianceCacheSide(b, u, side, w);
        if (w > 0.0) return true;
    }
    return false;
}
bool giRadianceAt(vec3 p, uint brick, vec3 uvw, uint cascade, out vec3 radiance) {
    return giRadianceAtSide(p, brick, uvw, cascade, vec3(0.0), radiance);
}
#endif

#ifdef GI_USES_BRICK_SH
GiSH giLoadBrickSH(uint brick, out float weight) {
    GiSH s;
    for (int i = 0; i < 9; ++i) {
        uvec2 v = giBrickSH[brick * 9u + uint(i)];
        vec2 rg = unpackHalf2x16(v.x), ba = unpackHalf2x16(v.y);
        s.c[i] = vec3(rg, ba.x);
        if (i == 0) weight = ba.y;
    }
    return s;
}

// The world cache around p: the up to 8 bricks of the trilinear cell around p (moved a quarter voxel off
// the surface) in the finest traced cascade that has any with samples, and their weights; bricks whose
// centre lies behind the surface are left out (no light from the other side of a wall). Returns the total
// weight (0: none); unused corners have weight 0. Callers read the coefficients they need
// (giWorldCacheCoefficient, giWorldCache), so a pass can split the nine over threads.
float giWorldCacheCorners(vec3 p, vec3 n, out uint bricks[8], out float weights[8]) {
    for (int k = 0; k < 8; ++k) {
        bricks[k] = 0u;
        weights[k] = 0.0;
    }
    for (uint c = giFrame.cascades.x; c <= giFrame.cascades.y; ++c) {
        BlSdfCascade info = blSdfTable.cascades[c];
        if (info.origin.w == 0) continue;
        float size = info.voxelSize.x;
        vec3 local = (p + n * (0.25 * size)) * info.voxelSize.y - 0.5;
        ivec3 cell = ivec3(floor(local));
        vec3 f = local - vec3(cell);
        float total = 0.0;
        for (int k = 0; k < 8; ++k) {
            ivec3 o = ivec3(k & 1, (k >> 1) & 1, k >> 2);
            ivec3 voxel = cell + o;
            uint brick = giBrickOfVoxel(voxel, c);
            if (brick == BL_SDF_UNBUILT) continue;
            vec3 centre = (vec3(voxel) + 0.5) * size;
            if (dot(centre - p, n) < -0.75 * size) continue;
            float samples = unpackHalf2x16(giBrickSH[brick * 9u].y).y;
            if (!(samples > 0.0)) continue;
            vec3 w3 = mix(1.0 - f, f, vec3(o));
            bricks[k] = brick;
            weights[k] = w3.x * w3.y * w3.z * min(samples, 4.0) + 1e-4;
            total += weights[k];
        }
        if (total > 0.0) return total;
    }
    return 0.0;
}

// Coefficient i of the world cache's SH at the corners found by giWorldCacheCorners (total > 0).
vec3 giWorldCacheCoefficient(uint bricks[8], float weights[8], float total, int i) {
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 8; ++k) {
        if (weights[k] <= 0.0) continue;
        uvec2 v = giBrickSH[bricks[k] * 9u + uint(i)];
        sum += vec3(unpackHalf2x16(v.x), unpackHalf2x16(v.y).x) * weights[k];
    }
    return sum / total;
}
#endif

#endif
