// Included by resolve_diffuse.comp and resolve_occlusion.comp (which defines BL_CONE_TRACE_OCCLUSION_ONLY).
// Full-resolution diffuse light from the sparse samples: each pixel weighs the four nearest blocks' samples by
// distance, normal agreement and distance from their surface's plane; a pixel none of them fits is listed for its own
// cones (VXGI's refinement: refine_list.glsl), traced here only where the list is full. Then the temporal blend with
// the reprojected history, where the surface there last frame is the same one.
#include "trace_common.glsl"
#include "history_blend.glsl"
#include "refine_list.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(4) uniform sampler2D lowDiffuse;
BL_TEXTURE(5) uniform usampler2D lowGuide;
BL_IMAGE(0, rgba16f) uniform writeonly image2D outputDiffuse;
BL_IMAGE(2, rg32ui) uniform writeonly uimage2D guide;
BL_STORAGE_BUFFER(0) RefineCounts { uint words[8]; } counts;
BL_STORAGE_BUFFER(1) RefineList { uint pixels[]; } list;
// The counts the next frame's resolve adds to (the previous frame's): zeroed here, so that no clear precedes the pass.
BL_STORAGE_BUFFER(2) NextRefineCounts { uint words[8]; } nextCounts;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel == ivec2(0))
        for (uint i = 0u; i < 8u; ++i) nextCounts.words[i] = (i == 1u || i == 2u) ? 1u : 0u;  // indirect y, z: 1
    if (any(greaterThanEqual(pixel, ivec2(trace.size.xy)))) return;
    float depth = texelFetch(gDepth, pixel, 0).r;
    if (isSky(depth)) {
        imageStore(outputDiffuse, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        storeHistory(pixel, vec4(0.0, 0.0, 0.0, 1.0));
        imageStore(guide, pixel, uvec4(NO_PIXEL_GUIDE, 0u, 0u));
        return;
    }
    vec3 position = worldPosition(pixel, depth);
    vec3 normal = surfaceNormal(pixel);
    float voxel = voxelSizeAt(position);

    float s = float(trace.size.z);
    vec2 lowCoord = (vec2(pixel) + 0.5 - vec2(trace.sparseOffset.xy) - 0.5) / s;  // in blocks, at sample centres
    ivec2 base = ivec2(floor(lowCoord));
    vec2 f = lowCoord - vec2(base);
    vec4 sum = vec4(0.0);
    float total = 0.0;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            ivec2 b = base + ivec2(i, j);
            if (any(lessThan(b, ivec2(0))) || any(greaterThanEqual(b, ivec2(trace.lowSize.xy)))) continue;
            vec3 p, n;
            if (!unpackGuide(texelFetch(lowGuide, b, 0), p, n)) continue;
            float bilinear = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y) + 1.0e-3;
            float normalWeight = pow(max(dot(normal, n), 0.0), 8.0);
            float planeWeight = max(1.0 - abs(dot(n, position - p)) / voxel, 0.0);
            float w = bilinear * normalWeight * planeWeight;
            sum += w * texelFetch(lowDiffuse, b, 0);
            total += w;
        }
    vec4 current;
    if (total > 1.0e-4) {
        current = sum / total;
    } else {  // no sample fits this pixel: listed for its own cones (refine_list.glsl), traced here if the list is full
        uint slot = atomicAdd(counts.words[REFINE_LISTED], 1u);
        if (slot < refineCapacity()) {
            list.pixels[slot] = packRefinePixel(pixel);
            atomicMax(counts.words[0], slot / refinePixelsPerGroup() + 1u);
            imageStore(guide, pixel, uvec4(packPixelGuide(depth, normal), 0u, 0u));
            return;
        }
        current = diffuseAt(position, normal, uintBitsToFloat(trace.sparseOffset.w));
    }

    vec4 result = blendHistory(pixel, position, normal, voxel, current);
    imageStore(outputDiffuse, pixel, result);
    storeHistory(pixel, result);
    imageStore(guide, pixel, uvec4(packPixelGuide(depth, normal), 0u, 0u));
}
