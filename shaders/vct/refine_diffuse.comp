#version 450
#extension GL_GOOGLE_include_directive : require
// The refinement's cones (refine_list.glsl): one invocation per cone of each listed pixel, so that a pixel's cones run
// side by side rather than one after another; each writes its light and ambient to the cone results.
#include "trace_common.glsl"
#include "refine_list.glsl"
layout(local_size_x = 64) in;
BL_READ_BUFFER(4) RefineCounts { uint words[8]; } counts;
BL_READ_BUFFER(5) RefineList { uint pixels[]; } list;
BL_STORAGE_BUFFER(0) RefineCones { vec4 results[]; } cones;  // pixel slot × cone count + cone

void main() {
    uint coneCount = diffuseConeCount();
    uint item = gl_GlobalInvocationID.x, slot = item / coneCount, k = item - slot * coneCount;
    if (slot >= min(counts.words[REFINE_LISTED], refineCapacity())) return;
    ivec2 pixel = unpackRefinePixel(list.pixels[slot]);
    vec3 position = worldPosition(pixel, texelFetch(gDepth, pixel, 0).r);
    vec3 normal = surfaceNormal(pixel);
    BlConeResult r = blTraceCone(diffuseCone(k, coneCount, position, normal, uintBitsToFloat(trace.sparseOffset.w), diffuseFrame(position, normal)));
    cones.results[item] = vec4(r.radiance, r.ambient);
}
