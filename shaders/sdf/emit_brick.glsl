// The end of the brick pass, shared by emit_distances.comp (a brick built by one group) and
// finalize_split_bricks.comp (a brick whose references were split over several groups): the group's shared
// minima and flags, and how a brick is stored from them. The including shader declares `table`, `baseMaps`,
// `brickMaps`, `brickAabbs`, `freeStack`, `counters` and `atlas`.
#ifndef BRICKLIGHT_SDF_EMIT_BRICK_GLSL
#define BRICKLIGHT_SDF_EMIT_BRICK_GLSL

shared uint best[512];       // squared distance to the nearest opaque triangle (float bits)
shared uint bestAlpha[512];  // ... to the nearest alpha-tested triangle
shared uint boxMin[3], boxMax[3], keep, alphaTested, opaqueCells[2];
shared uint baseSurface, ownSurface;  // brixels within an interval of the base's / the dynamic triangles' surfaces
shared vec4 albedoSum[256];    // rgb: albedo · pairs, w: pairs
shared vec3 emissionSum[256];

// Resets the group's minima and brick flags; ends with a barrier.
void blSdfBeginBrick(uint lane, float band) {
    best[lane] = floatBitsToUint(band * band);
    bestAlpha[lane] = floatBitsToUint(band * band);
    if (lane < 3u) {
        boxMin[lane] = 7u;
        boxMax[lane] = 0u;
    }
    if (lane < 2u) opaqueCells[lane] = 0u;
    if (lane == 0u) {
        keep = 0u;
        alphaTested = 0u;
        baseSurface = 0u;
        ownSurface = 0u;
    }
    barrier();
}

// The material sums over the group, left in albedoSum[0] / emissionSum[0]: the upper half folds onto the
// lower, then a tree.
void blSdfSumMaterials(uint lane, vec4 albedo, vec3 emission) {
    if (lane >= 256u) {
        albedoSum[lane - 256u] = albedo;
        emissionSum[lane - 256u] = emission;
    }
    barrier();
    if (lane < 256u) {
        albedoSum[lane] += albedo;
        emissionSum[lane] += emission;
    }
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
        if (lane < stride) {
            albedoSum[lane] += albedoSum[lane + stride];
            emissionSum[lane] += emissionSum[lane + stride];
        }
        barrier();
    }
}

// Stores the brick from the group's minima (best, bestAlpha) and material sums (a thread's `albedo`,
// `emission`): the R8 samples (the smaller of its own and the base brick's, if the voxel has one), the tight
// box, the alpha flag, the opaque cells and the material; a brick with no sample inside the band is freed.
void blSdfFinishBrick(uvec4 entry, uint cascade, uint physical, uint lane, float band, float brixel, vec4 albedo, vec3 emission) {
    ivec3 own = ivec3(gl_LocalInvocationID);
    barrier();
    float dOpaque = sqrt(uintBitsToFloat(best[lane])), dAlpha = sqrt(uintBitsToFloat(bestAlpha[lane]));
    float d = min(dOpaque, dAlpha);
    uint q = uint(floor(min(d, band) / band * 255.0 + 0.5));
    uint brick = entry.w;
    uint key = cascade * BL_SDF_CASCADE_VOXELS + physical;
    uint base = baseMaps[key];
    if (base < BL_SDF_FIRST_STATE) {
        // Within an interval of a surface of the base: the sample at most the rounding of one interval.
        uint qBase = uint(imageLoad(atlas, blSdfBrickTexel(base, table.header.y) + own).r * 255.0 + 0.5);
        if (qBase <= uint(floor(255.0 / BL_SDF_BAND_BRIXELS + 0.5))) atomicAdd(baseSurface, 1u);
        q = min(q, qBase);
    }
    if (d <= brixel) atomicAdd(ownSurface, 1u);
    imageStore(atlas, blSdfBrickTexel(brick, table.header.y) + own, vec4(float(q) / 255.0));
    if (q < 255u) atomicOr(keep, 1u);
    if (d <= brixel) {
        for (int axis = 0; axis < 3; ++axis) {
            atomicMin(boxMin[axis], uint(own[axis]));
            atomicMax(boxMax[axis], uint(own[axis]));
        }
    }
    if (dAlpha <= brixel) atomicOr(alphaTested, 1u);
    if (dOpaque <= brixel) {
        // Lattice points 0..7 over the voxel; cell k of 4 holds points 2k and 2k + 1 (k/4 <= i/7 < (k+1)/4).
        uvec3 cell = min(uvec3(own) * 4u / 7u, uvec3(3u));
        uint bit = (cell.z * 4u + cell.y) * 4u + cell.x;
        atomicOr(opaqueCells[bit >> 5], 1u << (bit & 31u));
    }
    blSdfSumMaterials(lane, albedo, emission);
    if (lane != 0u) return;
    uint materialAt = table.header.z * (1u + BL_SDF_OPAQUE_CELL_WORDS) + BL_SDF_MATERIAL_WORDS * entry.w;
    vec4 total = albedoSum[0];
    bool known = keep != 0u && total.w > 0.0;
    vec3 albedoMean = known ? clamp(total.rgb / total.w, 0.0, 1.0) : vec3(0.0);
    vec3 emissionMean = known ? emissionSum[0] / total.w : vec3(0.0);
    uint baseBox = BL_SDF_AABB_NONE;
    if (base < BL_SDF_FIRST_STATE) {
        baseBox = brickAabbs[base];
        uint baseMaterialAt = table.header.z * (1u + BL_SDF_OPAQUE_CELL_WORDS) + BL_SDF_MATERIAL_WORDS * base;
        uint baseAlbedo = brickAabbs[baseMaterialAt];
        if ((baseAlbedo >> 24) != 0u) {
            // Both known: the mean over both kinds' surface brixels; else whichever is known.
            float wBase = float(max(baseSurface, 1u)), wOwn = known ? float(ownSurface) : 0.0;
            vec3 baseEmission = blDecodeRgb9e5(brickAabbs[baseMaterialAt + 1u]);
            albedoMean = (unpackUnorm4x8(baseAlbedo).rgb * wBase + albedoMean * wOwn) / (wBase + wOwn);
            emissionMean = (baseEmission * wBase + emissionMean * wOwn) / (wBase + wOwn);
            known = true;
        }
        if (baseBox != BL_SDF_AABB_NONE) {
            // The base's box (stored grown by one and clamped, which commutes with the union) and its flags.
            if ((baseBox & BL_SDF_AABB_ALPHA_TESTED) != 0u) alphaTested = 1u;
            uint cells = table.header.z + 2u * base;
            opaqueCells[0] |= brickAabbs[cells];
            opaqueCells[1] |= brickAabbs[cells + 1u];
        }
    }
    brickAabbs[materialAt] = known ? packUnorm4x8(vec4(albedoMean, 1.0)) : 0u;
    brickAabbs[materialAt + 1u] = known ? blEncodeRgb9e5(emissionMean) : 0u;
    if (keep == 0u) {
        brickMaps[key] = BL_SDF_EMPTY;
        brickAabbs[brick] = BL_SDF_AABB_NONE;
        uint top = atomicAdd(counters[C_FREE_COUNT], 1u);
        freeStack[top] = brick;
        atomicAdd(counters[C_BRICKS_FREED], 1u);
    } else if (boxMin[0] > boxMax[0] && baseBox == BL_SDF_AABB_NONE) {
        brickAabbs[brick] = BL_SDF_AABB_NONE;  // distances only: no surface inside the voxel
    } else {
        uvec3 lo = uvec3(7u), hi = uvec3(0u);
        if (boxMin[0] <= boxMax[0]) {
            lo = uvec3(max(ivec3(boxMin[0], boxMin[1], boxMin[2]) - 1, ivec3(0)));
            hi = uvec3(min(ivec3(boxMax[0], boxMax[1], boxMax[2]) + 1, ivec3(7)));
        }
        if (baseBox != BL_SDF_AABB_NONE) {
            lo = min(lo, uvec3(baseBox, baseBox >> 3, baseBox >> 6) & 7u);
            hi = max(hi, uvec3(baseBox >> 9, baseBox >> 12, baseBox >> 15) & 7u);
        }
        uint flags = alphaTested != 0u ? BL_SDF_AABB_ALPHA_TESTED : 0u;
        brickAabbs[brick] = lo.x | (lo.y << 3) | (lo.z << 6) | (hi.x << 9) | (hi.y << 12) | (hi.z << 15) | flags;
        uint cells = table.header.z + 2u * brick;
        brickAabbs[cells] = opaqueCells[0];
        brickAabbs[cells + 1u] = opaqueCells[1];
    }
    atomicAdd(counters[C_VOXELS_BUILT], 1u);
}

#endif
