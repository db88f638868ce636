#version 450
#extension GL_GOOGLE_include_directive : require
#ifdef VULKAN
// Workgroup-scope atomics on shared memory (GLSL's atomicMin means device scope in SPIR-V).
#extension GL_KHR_memory_scope_semantics : require
#define SHARED_ATOMIC_MIN(mem, value) atomicMin(mem, value, gl_ScopeWorkgroup, gl_StorageSemanticsShared, gl_SemanticsRelaxed)
#else
#define SHARED_ATOMIC_MIN(mem, value) atomicMin(mem, value)
#endif
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
#include "bricklight/rgb9e5.glsl"
// One group per allocated brick. With many references (dense meshes) each thread takes references in turn
// and, for its triangle, visits only the brixels within the band of the triangle's box, keeping the
// smallest exact squared point-triangle distance per brixel with a shared-memory atomic minimum (squared
// distances of >= 0 floats order like their bits): the work is references x (brixels near each triangle),
// not references x 512. With few references (large triangles) each brixel evaluates all of them.
// Then one thread per brixel stores min(distance, band) / band in the R8 atlas, and the group derives the
// brick's tight AABB (brixels within one interval of a surface, grown by one); a brick with no brixel
// inside the band is freed (voxel EMPTY).
// Alpha-tested instances' triangles (scratch v1.w = 1) keep their own minimum: where one of them is within
// an interval of a brixel the brick is flagged BL_SDF_AABB_ALPHA_TESTED, and the 4³ cells whose brixels are
// within an interval of an opaque triangle are listed, so that a trace knows where a hit may be a cut-out
// texel of a card and where an opaque surface (the ground the grass stands on) is there for sure. The two
// minima cost no more atomics than one: each triangle updates only its own kind's.
// The brick's surface material (sdf::InstanceDesc::material) is the mean over the pairs (triangle with a
// material, brixel within one interval of it), each weighted 1 − distance / interval — a surface-area-weighted
// mean of the materials in the voxel, and continuous in the distances (a wall on a lattice plane has a row of
// brixels exactly one interval away: a step weight would count them or not by rounding) — summed per thread
// alongside the distances (no second distance evaluation) and then over the group.
// In an update's overlay round (dynamic instances, prepare_overlay.comp) the voxel has a base brick: its static
// geometry's field, built earlier and kept. The stored sample is then the smaller of the two (8-bit rounding is
// monotonic, so this equals rounding the exact minimum), and the box, the alpha flag and the opaque cells are
// the union of the base's and the dynamic triangles' (a brixel is within an interval of a surface of either
// kind exactly when it is within one of the minimum). The material mixes the two by their surface brixels.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 8) in;
BL_READ_BUFFER(0) Triangles { vec4 triangles[]; };
BL_READ_BUFFER(1) SortedReferences { uint sortedReferences[]; };
BL_READ_BUFFER(2) Touched { uvec4 touched[]; };
BL_READ_BUFFER(3) CascadeTable { BL_SDF_CASCADE_TABLE_BODY } table;
BL_READ_BUFFER(4) MaterialTable { vec4 materialTable[]; };  // per tag - 1: albedo, emission
BL_READ_BUFFER(5) BaseMaps { uint baseMaps[]; };
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) BrickAabbs { uint brickAabbs[]; };
BL_STORAGE_BUFFER(2) FreeStack { uint freeStack[]; };
BL_STORAGE_BUFFER(3) Counters { uint counters[]; };
BL_IMAGE(0, r8) uniform image3D atlas;

shared uint best[512];       // squared distance to the nearest opaque triangle (float bits)
shared uint bestAlpha[512];  // ... to the nearest alpha-tested triangle
shared uint boxMin[3], boxMax[3], keep, alphaTested, opaqueCells[2];
shared uint baseSurface, ownSurface;  // brixels within an interval of the base's / the dynamic triangles' surfaces
shared vec4 albedoSum[256];    // rgb: albedo · pairs, w: pairs
shared vec3 emissionSum[256];

// Adds `pairs` (triangle, brixel) pairs of the triangle with material tag `tag` to a thread's sums.
void addMaterial(uint tag, float pairs, inout vec4 albedo, inout vec3 emission) {
    if (tag == 0u || pairs == 0.0) return;
    albedo += vec4(materialTable[2u * (tag - 1u)].rgb, 1.0) * pairs;
    emission += materialTable[2u * (tag - 1u) + 1u].rgb * pairs;
}

void main() {
    uint t = gl_WorkGroupID.y * BL_SDF_WIDE_GROUPS + gl_WorkGroupID.x;
    if (t >= counters[C_TOUCHED_COUNT]) return;  // uniform per group
    uvec4 entry = touched[t];
    if (entry.w == BL_SDF_UNBUILT) return;
    uint lane = gl_LocalInvocationIndex;
    uint cascade = entry.x >> 24;
    uint physical = entry.x & 0xFFFFFFu;
    ivec3 origin = table.cascades[cascade].origin.xyz;
    ivec3 slot = ivec3(physical % 64u, (physical / 64u) % 64u, physical / 4096u);
    ivec3 voxel = origin + ((slot - origin) & ivec3(BL_SDF_CASCADE_RES - 1));
    float vs = table.cascades[cascade].voxelSize.x;
    float band = table.cascades[cascade].voxelSize.w;
    float brixel = vs / 7.0;
    vec3 voxelMin = vec3(voxel) * vs;

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

    ivec3 own = ivec3(gl_LocalInvocationID);
    vec4 albedo = vec4(0.0);
    vec3 emission = vec3(0.0);
    float near2 = brixel * brixel;  // a brixel within one interval of a triangle is on its surface
    if (entry.y <= 32u) {
        // Few references (large triangles): every brixel evaluates all of them, so all threads work.
        vec3 p = (vec3(voxel) + vec3(own) / 7.0) * vs;
        float d2 = band * band, d2Alpha = band * band;
        for (uint r = 0u; r < entry.y; ++r) {
            uint tri = sortedReferences[entry.z + r];
            vec4 b = triangles[3u * tri + 1u], c = triangles[3u * tri + 2u];
            float e2 = blPointTriangleDistanceSq(p, triangles[3u * tri].xyz, b.xyz, c.xyz);
            if (b.w > 0.5) d2Alpha = min(d2Alpha, e2);
            else d2 = min(d2, e2);
            if (e2 < near2) addMaterial(uint(c.w), 1.0 - sqrt(e2) / brixel, albedo, emission);
        }
        best[lane] = floatBitsToUint(d2);
        bestAlpha[lane] = floatBitsToUint(d2Alpha);
    } else {
        for (uint r = lane; r < entry.y; r += 512u) {
            uint tri = sortedReferences[entry.z + r];
            vec4 bw = triangles[3u * tri + 1u], cw = triangles[3u * tri + 2u];
            vec3 a = triangles[3u * tri].xyz, b = bw.xyz, c = cw.xyz;
            float pairs = 0.0;
            bool alphaTri = bw.w > 0.5;
            // Brixels whose lattice point lies within the band of the triangle's box.
            vec3 lo = (min(a, min(b, c)) - band - voxelMin) / brixel;
            vec3 hi = (max(a, max(b, c)) + band - voxelMin) / brixel;
            ivec3 i0 = clamp(ivec3(ceil(lo)), ivec3(0), ivec3(7));
            ivec3 i1 = clamp(ivec3(floor(hi)), ivec3(0), ivec3(7));
            // A bounding sphere of the triangle culls the box's corners (about half of its brixels for
            // triangles smaller than a brixel) before the exact test.
            vec3 centre = (a + b + c) / 3.0;
            float reach = sqrt(max(blDot2(a - centre), max(blDot2(b - centre), blDot2(c - centre)))) + band;
            for (int z = i0.z; z <= i1.z; ++z)
                for (int y = i0.y; y <= i1.y; ++y)
                    for (int x = i0.x; x <= i1.x; ++x) {
                        vec3 p = (vec3(voxel) + vec3(x, y, z) / 7.0) * vs;
                        if (blDot2(p - centre) > reach * reach) continue;
                        uint index = uint((z * 8 + y) * 8 + x);
                        float d2 = blPointTriangleDistanceSq(p, a, b, c);
                        if (d2 < near2) pairs += 1.0 - sqrt(d2) / brixel;
                        if (alphaTri) {
                            if (floatBitsToUint(d2) < bestAlpha[index]) SHARED_ATOMIC_MIN(bestAlpha[index], floatBitsToUint(d2));
                        } else if (floatBitsToUint(d2) < best[index]) {
                            SHARED_ATOMIC_MIN(best[index], floatBitsToUint(d2));
                        }
                    }
            addMaterial(uint(cw.w), pairs, albedo, emission);
        }
    }
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
    // The material sums over the group: the upper half folds onto the lower, then a tree.
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
