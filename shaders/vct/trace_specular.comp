#version 450
#extension GL_GOOGLE_include_directive : require
// Specular light: one cone per pixel along the mirror direction, as wide as the roughness says (VXGI 1.0:
// coneFactor = roughness² · √π, roughness clamped to the largest a cone takes), then the temporal blend with the
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
    vec4 r4 = texelFetch(gRoughness, pixel, 0);
    uint channel = uint(trace.normalUnpackScale.w);
    float roughness = clamp(channel == 0u ? r4.x : (channel == 1u ? r4.y : (channel == 2u ? r4.z : r4.w)), 0.0, trace.normalUnpackOffset.w);
    vec3 view = normalize(trace.eye.xyz - position);
    vec3 direction = reflect(-view, normal);
    float coneFactor = max(roughness * roughness * 1.7724539, 0.01);
    BlCone cone = coneAt(position, normal, direction, coneFactor);
    cone.tracingStep = uintBitsToFloat(trace.sparseOffset.z);
    BlConeResult r = blTraceCone(cone);
    vec4 current = vec4(r.radiance, 1.0);

    ivec2 previous;
    vec4 result = current;
    if ((trace.lowSize.w & FLAG_RESET) == 0u && previousPixel(pixel, position, previous)) {
        vec3 p, n;
        float voxel = voxelSizeAt(position);
        if (unpackGuide(texelFetch(previousGuide, previous, 0), p, n) && distance(p, position) < 0.5 * voxel && dot(n, normal) > 0.9)
            result = mix(current, texelFetch(previousHistory, previous, 0), clamp(trace.limits.z, 0.0, 0.98));
    }
    imageStore(outputSpecular, pixel, result);
    imageStore(history, pixel, result);
}
