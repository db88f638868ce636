// The temporal blend of the diffuse passes (resolve_diffuse.comp, resolve_refined.comp), included after
// trace_common.glsl: last frame's history and guide at texture slots 6 and 7.
BL_TEXTURE(6) uniform sampler2D previousHistory;
BL_TEXTURE(7) uniform usampler2D previousGuide;

// A pixel's light blended with its reprojected history (the temporal weight), where the surface there last frame is the
// same one: within half a voxel (`voxel` world units, the level's at the surface) and facing the same way.
vec4 blendHistory(ivec2 pixel, vec3 position, vec3 normal, float voxel, vec4 current) {
    ivec2 previous;
    if ((trace.lowSize.w & FLAG_RESET) != 0u || !previousPixel(pixel, position, previous)) return current;
    vec3 p, n;
    if (unpackGuide(texelFetch(previousGuide, previous, 0), p, n) && distance(p, position) < 0.5 * voxel && dot(n, normal) > 0.9)
        return mix(current, texelFetch(previousHistory, previous, 0), clamp(trace.limits.z, 0.0, 0.98));
    return current;
}
