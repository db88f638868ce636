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
// A reference to a mover grid's chunk (mover_grid.glsl) stands for a rigid mover's whole mesh: each brixel
// takes its distance from the grid, as an opaque triangle of the mover's material would give it.
// A brick with more than BL_SDF_REFS_PER_GROUP references (a dense mesh in a coarse voxel: a 100k-triangle
// object's every triangle in one brick) is split by allocate_bricks.comp into chunks of that many, one group
// each after the touched voxels' groups: a chunk's group takes the minima of its references and adds them to
// the brick's in global memory (atomic minimum), with its material sums beside; finalize_split_bricks.comp
// then stores the brick. One group per brick would leave the device idle behind a few such bricks.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 8) in;
BL_READ_BUFFER(0) Triangles { vec4 triangles[]; };
BL_READ_BUFFER(1) SortedReferences { uint sortedReferences[]; };
BL_READ_BUFFER(2) Touched { uvec4 touched[]; };
BL_READ_BUFFER(3) CascadeTable { BL_SDF_CASCADE_TABLE_BODY } table;
BL_READ_BUFFER(4) MaterialTable { vec4 materialTable[]; };  // per tag - 1: albedo, emission
BL_READ_BUFFER(5) BaseMaps { uint baseMaps[]; };
BL_READ_BUFFER(6) SplitBricks { uvec4 splitBricks[]; };  // touched index, first split work item, chunks
BL_READ_BUFFER(7) SplitWork { uvec2 splitWork[]; };      // split brick, chunk
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) BrickAabbs { uint brickAabbs[]; };
BL_STORAGE_BUFFER(2) FreeStack { uint freeStack[]; };
BL_STORAGE_BUFFER(3) Counters { uint counters[]; };
BL_STORAGE_BUFFER(4) SplitMinima { uint splitMinima[]; };      // 1024 per split brick (opaque, alpha-tested)
BL_STORAGE_BUFFER(5) SplitMaterials { vec4 splitMaterials[]; };  // 2 per split work item
BL_STORAGE_BUFFER(6) MoverGridTable { uvec4 moverGridTable[]; };  // read only
BL_STORAGE_BUFFER(7) MoverGridData { uint moverGridData[]; };      // read only
BL_IMAGE(0, r8) uniform image3D atlas;

#include "emit_brick.glsl"
#define BL_SDF_MOVER_SAMPLING
#include "mover_grid.glsl"

shared uint moverList[512];  // a brick's mover chunks (many-reference path)
shared uint moverCount;

// Adds `pairs` (triangle, brixel) pairs of the triangle with material tag `tag` to a thread's sums.
void addMaterial(uint tag, float pairs, inout vec4 albedo, inout vec3 emission) {
    if (tag == 0u || pairs == 0.0) return;
    albedo += vec4(materialTable[2u * (tag - 1u)].rgb, 1.0) * pairs;
    emission += materialTable[2u * (tag - 1u) + 1u].rgb * pairs;
}

void main() {
    uint g = gl_WorkGroupID.y * BL_SDF_WIDE_GROUPS + gl_WorkGroupID.x;
    uint touchedCount = counters[C_TOUCHED_COUNT];
    uint begin = 0u, end = 0u, split = BL_SDF_NO_SPLIT, work = 0u;
    uvec4 entry;
    if (g < touchedCount) {  // uniform per group
        entry = touched[g];
        if (entry.w == BL_SDF_UNBUILT || (entry.y & BL_SDF_SPLIT_FLAG) != 0u) return;
        end = entry.y;
    } else {
        work = g - touchedCount;
        if (work >= counters[C_SPLIT_WORK_CURSOR]) return;
        uvec2 item = splitWork[work];
        split = item.x;
        entry = touched[splitBricks[split].x];
        begin = item.y * BL_SDF_REFS_PER_GROUP;
        end = min(entry.y & ~BL_SDF_SPLIT_FLAG, begin + BL_SDF_REFS_PER_GROUP);
    }
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
    blSdfBeginBrick(lane, band);

    ivec3 own = ivec3(gl_LocalInvocationID);
    vec4 albedo = vec4(0.0);
    vec3 emission = vec3(0.0);
    float near2 = brixel * brixel;  // a brixel within one interval of a triangle is on its surface
    if (end - begin <= 32u) {
        // Few references (large triangles): every brixel evaluates all of them, so all threads work.
        vec3 p = (vec3(voxel) + vec3(own) / 7.0) * vs;
        float d2 = band * band, d2Alpha = band * band;
        for (uint r = begin; r < end; ++r) {
            uint tri = sortedReferences[entry.z + r];
            vec4 b = triangles[3u * tri + 1u], c = triangles[3u * tri + 2u];
            bool mover = b.w > BL_SDF_MOVER_TAG - 0.5;
            float e2 = mover ? blSdfMoverDistanceSq(uint(b.w - BL_SDF_MOVER_TAG + 0.5), cascade, p, band * band)
                             : blPointTriangleDistanceSq(p, triangles[3u * tri].xyz, b.xyz, c.xyz);
            if (b.w > 0.5 && !mover) d2Alpha = min(d2Alpha, e2);
            else d2 = min(d2, e2);
            if (e2 < near2) addMaterial(uint(c.w), 1.0 - sqrt(e2) / brixel, albedo, emission);
        }
        best[lane] = floatBitsToUint(d2);
        bestAlpha[lane] = floatBitsToUint(d2Alpha);
    } else {
        // Mover chunks among many references (many movers in a coarse voxel, or movers beside triangles): listed
        // first, then every thread samples them at its own brixel.
        if (lane == 0u) moverCount = 0u;
        barrier();
        for (uint r = begin + lane; r < end; r += 512u) {
            uint tri = sortedReferences[entry.z + r];
            if (triangles[3u * tri + 1u].w > BL_SDF_MOVER_TAG - 0.5) {
                uint k = atomicAdd(moverCount, 1u);
                if (k < 512u) moverList[k] = tri;
            }
        }
        barrier();
        uint listed = moverCount <= 512u ? moverCount : 0u;  // more: each sampled by one thread, below
        if (listed > 0u) {
            vec3 p = (vec3(voxel) + vec3(own) / 7.0) * vs;
            float d2 = uintBitsToFloat(best[lane]);
            for (uint k = 0u; k < listed; ++k) {
                uint tri = moverList[k];
                float e2 = blSdfMoverDistanceSq(uint(triangles[3u * tri + 1u].w - BL_SDF_MOVER_TAG + 0.5), cascade, p, band * band);
                d2 = min(d2, e2);
                if (e2 < near2) addMaterial(uint(triangles[3u * tri + 2u].w), 1.0 - sqrt(e2) / brixel, albedo, emission);
            }
            best[lane] = floatBitsToUint(d2);
        }
        barrier();
        for (uint r = begin + lane; r < end; r += 512u) {
            uint tri = sortedReferences[entry.z + r];
            vec4 bw = triangles[3u * tri + 1u], cw = triangles[3u * tri + 2u];
            if (bw.w > BL_SDF_MOVER_TAG - 0.5) {
                // Sampled above, unless there were more than 512: then this thread samples it at all 512 brixels.
                if (moverCount <= 512u) continue;
                uint m = uint(bw.w - BL_SDF_MOVER_TAG + 0.5);
                float moverPairs = 0.0;
                for (uint index = 0u; index < 512u; ++index) {
                    vec3 p = (vec3(voxel) + vec3(index & 7u, (index >> 3) & 7u, index >> 6) / 7.0) * vs;
                    float d2 = blSdfMoverDistanceSq(m, cascade, p, band * band);
                    if (d2 < near2) moverPairs += 1.0 - sqrt(d2) / brixel;
                    if (floatBitsToUint(d2) < best[index]) SHARED_ATOMIC_MIN(best[index], floatBitsToUint(d2));
                }
                addMaterial(uint(cw.w), moverPairs, albedo, emission);
                continue;
            }
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
    if (split == BL_SDF_NO_SPLIT) {
        blSdfFinishBrick(entry, cascade, physical, lane, band, brixel, albedo, emission);
        return;
    }
    // A chunk of a split brick: its minima into the brick's, its material sums beside.
    barrier();
    uint at = 1024u * split + lane;
    if (best[lane] < splitMinima[at]) atomicMin(splitMinima[at], best[lane]);
    if (bestAlpha[lane] < splitMinima[at + 512u]) atomicMin(splitMinima[at + 512u], bestAlpha[lane]);
    blSdfSumMaterials(lane, albedo, emission);
    if (lane == 0u) {
        splitMaterials[2u * work] = albedoSum[0];
        splitMaterials[2u * work + 1u] = vec4(emissionSum[0], 0.0);
    }
}
