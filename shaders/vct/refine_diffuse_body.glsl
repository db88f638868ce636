// Included by refine_diffuse.comp and refine_occlusion.comp (which defines BL_CONE_TRACE_OCCLUSION_ONLY).
// The refined pixels (refine_list.glsl): a group holds whole pixels, one invocation per cone, so that a pixel's cones
// run side by side rather than one after another; then each pixel's first invocation sums its cones in order — as
// diffuseAt does, to the bit — and blends the sum with the history as the resolve blends the others.
#include "trace_common.glsl"
#include "history_blend.glsl"
#include "refine_list.glsl"
layout(local_size_x = REFINE_GROUP) in;
BL_READ_BUFFER(4) RefineCounts { uint words[8]; } counts;
BL_READ_BUFFER(5) RefineList { uint pixels[]; } list;
BL_IMAGE(0, rgba16f) uniform writeonly image2D outputDiffuse;

shared vec4 coneResults[REFINE_GROUP];  // light and ambient of each invocation's cone

void main() {
    uint coneCount = diffuseConeCount(), local = gl_LocalInvocationID.x;
    uint pixelInGroup = local / coneCount, k = local - pixelInGroup * coneCount;
    uint slot = gl_WorkGroupID.x * refinePixelsPerGroup() + pixelInGroup;
    bool listed = pixelInGroup < refinePixelsPerGroup() && slot < min(counts.words[REFINE_LISTED], refineCapacity());
    ivec2 pixel = ivec2(0);
    vec3 position = vec3(0.0), normal = vec3(0.0, 0.0, 1.0);
    if (listed) {
        pixel = unpackRefinePixel(list.pixels[slot]);
        position = worldPosition(pixel, texelFetch(gDepth, pixel, 0).r);
        normal = surfaceNormal(pixel);
        BlConeResult r = blTraceCone(diffuseCone(k, coneCount, position, normal, uintBitsToFloat(trace.sparseOffset.w), diffuseFrame(position, normal)));
        coneResults[local] = vec4(r.radiance, r.ambient);
    }
    barrier();
    if (!listed || k != 0u) return;
    vec4 sum = vec4(0.0);
    for (uint c = 0u; c < coneCount; ++c) sum += coneResults[local + c];
    vec4 result = blendHistory(pixel, position, normal, voxelSizeAt(position), sum / float(coneCount));
    imageStore(outputDiffuse, pixel, result);
    storeHistory(pixel, result);
}
