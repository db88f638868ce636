#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
#include "bricklight/rgb9e5.glsl"
// One group per brick whose references emit_distances.comp split over several groups: the brick's minima
// (summed up by the chunks' atomic minima) and the chunks' material sums become the brick, stored as a brick
// built by one group is (emit_brick.glsl). The minima go back to +inf for the next round.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 8) in;
BL_READ_BUFFER(0) Touched { uvec4 touched[]; };
BL_READ_BUFFER(1) CascadeTable { BL_SDF_CASCADE_TABLE_BODY } table;
BL_READ_BUFFER(2) BaseMaps { uint baseMaps[]; };
BL_READ_BUFFER(3) SplitBricks { uvec4 splitBricks[]; };  // touched index, first split work item, chunks
BL_READ_BUFFER(4) SplitMaterials { vec4 splitMaterials[]; };
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) BrickAabbs { uint brickAabbs[]; };
BL_STORAGE_BUFFER(2) FreeStack { uint freeStack[]; };
BL_STORAGE_BUFFER(3) Counters { uint counters[]; };
BL_STORAGE_BUFFER(4) SplitMinima { uint splitMinima[]; };
BL_IMAGE(0, r8) uniform image3D atlas;

#include "emit_brick.glsl"

void main() {
    uint split = gl_WorkGroupID.y * BL_SDF_WIDE_GROUPS + gl_WorkGroupID.x;
    if (split >= min(counters[C_SPLIT_CURSOR], BL_SDF_MAX_SPLIT_BRICKS)) return;  // uniform per group
    uvec4 brick = splitBricks[split];
    uvec4 entry = touched[brick.x];
    uint lane = gl_LocalInvocationIndex;
    uint cascade = entry.x >> 24;
    uint physical = entry.x & 0xFFFFFFu;
    float vs = table.cascades[cascade].voxelSize.x;
    float band = table.cascades[cascade].voxelSize.w;
    blSdfBeginBrick(lane, band);
    uint at = 1024u * split + lane;
    best[lane] = min(splitMinima[at], floatBitsToUint(band * band));
    bestAlpha[lane] = min(splitMinima[at + 512u], floatBitsToUint(band * band));
    splitMinima[at] = BL_SDF_SPLIT_MINIMUM_CLEAR;
    splitMinima[at + 512u] = BL_SDF_SPLIT_MINIMUM_CLEAR;
    vec4 albedo = vec4(0.0);
    vec3 emission = vec3(0.0);
    for (uint chunk = lane; chunk < brick.z; chunk += 512u) {
        albedo += splitMaterials[2u * (brick.y + chunk)];
        emission += splitMaterials[2u * (brick.y + chunk) + 1u].rgb;
    }
    blSdfFinishBrick(entry, cascade, physical, lane, band, vs / 7.0, albedo, emission);
}
