// Included by trace_diffuse.comp, trace_diffuse_sdf.comp (which defines VCT_SDF_OCCLUSION) and trace_occlusion.comp.
// Sparse diffuse tracing (VXGI's tracingSparsity): one pixel of each N×N block (a different one each frame)
// traces the diffuse cones; its surface goes to the guide, for resolve_diffuse.comp's geometry-aware upsample.
#include "trace_common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
BL_IMAGE(0, rgba16f) uniform writeonly image2D lowDiffuse;  // rgb: irradiance / π, a: ambient
BL_IMAGE(1, rgba32ui) uniform writeonly uimage2D lowGuide;

void main() {
    ivec2 block = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(block, ivec2(trace.lowSize.xy)))) return;
    ivec2 pixel = min(block * int(trace.size.z) + ivec2(trace.sparseOffset.xy), ivec2(trace.size.xy) - 1);
    float depth = texelFetch(gDepth, pixel, 0).r;
    if (isSky(depth)) {
        imageStore(lowDiffuse, block, vec4(0.0, 0.0, 0.0, 1.0));
        imageStore(lowGuide, block, NO_GUIDE);
        return;
    }
    vec3 position = worldPosition(pixel, depth);
    vec3 normal = surfaceNormal(pixel);
    imageStore(lowDiffuse, block, diffuseAt(position, normal, uintBitsToFloat(trace.sparseOffset.w)));
    imageStore(lowGuide, block, packGuide(position, normal));
}
