// Included by trace_specular.comp and trace_specular_sdf.comp (which defines VCT_SDF_OCCLUSION).
// Specular light: one cone per pixel along the mirror direction (specularCone, trace_common.glsl), then the temporal blend with the
// reprojected history (the guide resolve_diffuse.comp wrote last frame says whether the surface is the same).
#include "trace_common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(6) uniform sampler2D previousHistory;
BL_TEXTURE(7) uniform usampler2D previousGuide;
BL_IMAGE(0, rgba16f) uniform writeonly image2D outputSpecular;
BL_IMAGE(1, rgba16f) uniform writeonly image2D history;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(trace.size.xy)))) return;
    float depth = texelFetch(gDepth, pixel, 0).r;
    if (isSky(depth)) {
        imageStore(outputSpecular, pixel, vec4(0.0));
        imageStore(history, pixel, vec4(0.0));
        return;
    }
    vec3 position = worldPosition(pixel, depth);
    vec3 normal = surfaceNormal(pixel);
    BlConeResult r = blTraceCone(specularCone(pixel, position, normal));
    vec4 current = vec4(r.radiance, 1.0);

    ivec2 previous;
    vec4 result = current;
    if ((trace.lowSize.w & FLAG_RESET) == 0u && previousPixel(pixel, position, previous)) {
        if (sameSurfaceLastFrame(texelFetch(previousGuide, previous, 0).xy, previous, position, normal, voxelSizeAt(position)))
            result = mix(current, texelFetch(previousHistory, previous, 0), clamp(trace.limits.z, 0.0, 0.98));
    }
    imageStore(outputSpecular, pixel, result);
    imageStore(history, pixel, result);
}
