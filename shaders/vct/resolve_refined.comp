#version 450
#extension GL_GOOGLE_include_directive : require
// The refined pixels' light (refine_list.glsl): each listed pixel sums its cones in order — as diffuseAt does, to the
// bit — and is blended with its history as resolve_diffuse.comp blends the others.
#include "trace_common.glsl"
#include "history_blend.glsl"
#include "refine_list.glsl"
layout(local_size_x = 64) in;
BL_READ_BUFFER(4) RefineCounts { uint words[8]; } counts;
BL_READ_BUFFER(5) RefineList { uint pixels[]; } list;
BL_READ_BUFFER(0) RefineCones { vec4 results[]; } cones;
BL_IMAGE(0, rgba16f) uniform writeonly image2D outputDiffuse;
BL_IMAGE(1, rgba16f) uniform writeonly image2D history;

void main() {
    uint slot = gl_GlobalInvocationID.x, coneCount = diffuseConeCount();
    if (slot >= min(counts.words[REFINE_LISTED], refineCapacity())) return;
    ivec2 pixel = unpackRefinePixel(list.pixels[slot]);
    vec3 position = worldPosition(pixel, texelFetch(gDepth, pixel, 0).r);
    vec3 normal = surfaceNormal(pixel);
    vec4 sum = vec4(0.0);
    for (uint k = 0u; k < coneCount; ++k) sum += cones.results[slot * coneCount + k];
    vec4 result = blendHistory(pixel, position, normal, voxelSizeAt(position), sum / float(coneCount));
    imageStore(outputDiffuse, pixel, result);
    imageStore(history, pixel, result);
}
