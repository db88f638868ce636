// The temporal blend of the diffuse passes (resolve_diffuse_body.glsl, refine_diffuse_body.glsl), included after
// trace_common.glsl: last frame's history and guide at texture slots 6 and 7, this frame's history at image slot 1.
// An occlusion-only tracer (BL_CONE_TRACE_OCCLUSION_ONLY: voxel AO) keeps only the ambient, in an R16_FLOAT history.
BL_TEXTURE(6) uniform sampler2D previousHistory;
BL_TEXTURE(7) uniform usampler2D previousGuide;
#ifdef BL_CONE_TRACE_OCCLUSION_ONLY
BL_IMAGE(1, r16f) uniform writeonly image2D history;
void storeHistory(ivec2 pixel, vec4 value) { imageStore(history, pixel, vec4(value.a)); }
vec4 historyAt(ivec2 pixel) { return vec4(0.0, 0.0, 0.0, texelFetch(previousHistory, pixel, 0).r); }
#else
BL_IMAGE(1, rgba16f) uniform writeonly image2D history;
void storeHistory(ivec2 pixel, vec4 value) { imageStore(history, pixel, value); }
vec4 historyAt(ivec2 pixel) { return texelFetch(previousHistory, pixel, 0); }
#endif

// A pixel's light blended with its reprojected history (the temporal weight), where the surface there last frame is the
// same one (sameSurfaceLastFrame).
vec4 blendHistory(ivec2 pixel, vec3 position, vec3 normal, float voxel, vec4 current) {
    ivec2 previous;
    if ((trace.lowSize.w & FLAG_RESET) != 0u || !previousPixel(pixel, position, previous)) return current;
    if (sameSurfaceLastFrame(texelFetch(previousGuide, previous, 0).xy, previous, position, normal, voxel))
        return mix(current, historyAt(previous), clamp(trace.limits.z, 0.0, 0.98));
    return current;
}
