#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// One thread, between passes, so that the following dispatches size themselves on the GPU:
//   stage 0 (after counting references): args for one thread per touched voxel;
//   stage 1 (after allocating bricks): commits the bricks taken from the free list and writes args for
//            the brick pass (one group per touched voxel and per chunk of a split one), one thread per
//            stored reference, and one group per split brick.
layout(local_size_x = 1) in;
BL_CONSTANTS(0) uniform Params { uint stage; uint maxReferences; } params;
BL_STORAGE_BUFFER(0) Counters { uint counters[]; };
BL_STORAGE_BUFFER(1) Args { uint args[]; };

void wide(uint slot, uint groups) {
    args[slot] = min(groups, BL_SDF_WIDE_GROUPS);
    args[slot + 1u] = (groups + BL_SDF_WIDE_GROUPS - 1u) / BL_SDF_WIDE_GROUPS;
    args[slot + 2u] = 1u;
}

void main() {
    uint touchedCount = counters[C_TOUCHED_COUNT];
    if (params.stage == 0u) {
        wide(ARGS_PER_TOUCHED_64, (touchedCount + 63u) / 64u);
        counters[C_FREE_AT_ALLOCATION] = counters[C_FREE_COUNT];
        return;
    }
    uint freeCount = counters[C_FREE_COUNT];
    counters[C_FREE_COUNT] = freeCount - min(counters[C_ALLOC_CURSOR], freeCount);
    uint stored = min(counters[C_REF_CURSOR], params.maxReferences);
    counters[C_REFS_STORED] = stored;  // this round's, for the scatter pass
    counters[C_REFS_IN_UPDATE] += stored;  // over the update's rounds (full, then overlay), for the stats
    // The brick pass: a group per touched voxel, then one per chunk of the split ones; their finalize.
    wide(ARGS_PER_TOUCHED_BRICK, touchedCount + counters[C_SPLIT_WORK_CURSOR]);
    wide(ARGS_PER_SPLIT_BRICK, min(counters[C_SPLIT_CURSOR], BL_SDF_MAX_SPLIT_BRICKS));
    wide(ARGS_PER_REFERENCE_64, (stored + 63u) / 64u);
}
