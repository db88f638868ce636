#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// One thread per touched voxel: takes a brick from the top of the free stack (the stack only shrinks in
// this pass; prepare_args commits the count) and a range of the sorted reference list. A voxel that
// lost its references to the budget, or finds the pool empty, stays UNBUILT (deferred). The brick's owner
// entry gets the voxel and the brick's next allocation generation. A voxel with more references than one
// group of the brick pass should take is split into chunks (emit_distances.comp), while there is room.
layout(local_size_x = 64) in;
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) VoxelRefs { uint voxelRefs[]; };
BL_STORAGE_BUFFER(2) Touched { uvec4 touched[]; };
BL_STORAGE_BUFFER(3) Counters { uint counters[]; };
BL_STORAGE_BUFFER(4) FreeStack { uint freeStack[]; };
BL_STORAGE_BUFFER(5) BrickOwners { uint brickOwners[]; };
BL_STORAGE_BUFFER(6) SplitBricks { uvec4 splitBricks[]; };  // touched index, first split work item, chunks
BL_STORAGE_BUFFER(7) SplitWork { uvec2 splitWork[]; };      // split brick, chunk

void main() {
    uint t = gl_GlobalInvocationID.y * (BL_SDF_WIDE_GROUPS * 64u) + gl_GlobalInvocationID.x;
    if (t >= counters[C_TOUCHED_COUNT]) return;
    uvec4 entry = touched[t];
    uint key = (entry.x >> 24) * BL_SDF_CASCADE_VOXELS + (entry.x & 0xFFFFFFu);
    if (brickMaps[key] != BL_SDF_BUILDING) return;  // deferred while counting
    uint available = counters[C_FREE_AT_ALLOCATION];
    uint k = atomicAdd(counters[C_ALLOC_CURSOR], 1u);
    if (k >= available) {
        brickMaps[key] = BL_SDF_UNBUILT;
        atomicAdd(counters[C_VOXELS_DEFERRED], 1u);
        return;
    }
    uint brick = freeStack[available - 1u - k];
    uint count = voxelRefs[2u * key];
    uint first = atomicAdd(counters[C_SORTED_CURSOR], count);
    uint flag = 0u;
    if (count > BL_SDF_REFS_PER_GROUP) {
        uint split = atomicAdd(counters[C_SPLIT_CURSOR], 1u);
        if (split < BL_SDF_MAX_SPLIT_BRICKS) {
            uint chunks = (count + BL_SDF_REFS_PER_GROUP - 1u) / BL_SDF_REFS_PER_GROUP;
            uint work = atomicAdd(counters[C_SPLIT_WORK_CURSOR], chunks);
            splitBricks[split] = uvec4(t, work, chunks, 0u);
            for (uint chunk = 0u; chunk < chunks; ++chunk) splitWork[work + chunk] = uvec2(split, chunk);
            flag = BL_SDF_SPLIT_FLAG;
            atomicAdd(counters[C_BRICKS_SPLIT], 1u);
        }
    }
    touched[t] = uvec4(entry.x, count | flag, first, brick);
    brickMaps[key] = brick;
    // A new generation, so that caches keyed by brick id see a new owner even where the brick comes back
    // to the voxel it was freed from (sdf_layout.glsl).
    uint previous = brickOwners[brick];
    uint generation = previous == BL_SDF_NO_OWNER ? 0u : ((previous >> BL_SDF_OWNER_GENERATION_SHIFT) + 1u) % BL_SDF_OWNER_GENERATIONS;
    brickOwners[brick] = entry.x | generation << BL_SDF_OWNER_GENERATION_SHIFT;
    atomicAdd(counters[C_BRICKS_ALLOCATED], 1u);
}
