#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
#include "bricklight/trace.glsl"
// The camera self-check (docs/gi.md, "Camera conventions"): 16×16 pixels spread over the application's depth
// buffer are rebuilt into world positions exactly as every GI pass rebuilds them, and each is looked up in
// the distance field. With the right camera they lie on the surfaces the field holds; a missing y-flip, a
// [-1, 1] depth projection or transposed matrices put most of them in empty space. Counts: on a surface,
// off every surface, not decidable (outside the cascades or not built yet), sky.
layout(local_size_x = 16, local_size_y = 16) in;
BL_TEXTURE(0) uniform sampler2D inputDepth;
BL_STORAGE_BUFFER(0) CameraCheck {
    uint counts[4];
} check;

void main() {
    uvec2 displaySize = giFrame.size.zw;
    uvec2 pixel = min(uvec2((vec2(gl_LocalInvocationID.xy) + 0.5) / 16.0 * vec2(displaySize)), displaySize - 1u);
    float depth = texelFetch(inputDepth, ivec2(pixel), 0).r;
    if (giIsSky(depth)) {
        atomicAdd(check.counts[3], 1u);
        return;
    }
    vec3 p = giWorldPosition((vec2(pixel) + 0.5) / vec2(displaySize), depth, giCamera.inverseViewProjection);
    // The same pixel on the near plane must be next to the camera: the position rebuilding is a camera
    // through cameraPosition. (Matrices that are not one, transposed ones, can put `p` anywhere, even on a
    // surface.)
    vec3 onNearPlane = giWorldPosition((vec2(pixel) + 0.5) / vec2(displaySize), giHasFlag(GI_FLAG_REVERSED_DEPTH) ? 1.0 : 0.0,
                                       giCamera.inverseViewProjection);
    if (!giFinite(p) || !giFinite(onNearPlane) ||
        !(distance(onNearPlane, giFrame.camera.xyz) <= 0.5 * distance(p, giFrame.camera.xyz))) {
        atomicAdd(check.counts[1], 1u);
        return;
    }
    for (uint c = 0u; c < blSdfTable.header.x; ++c) {
        float d = blSdfDistance(p, c);
        if (d < 0.0) continue;  // outside this cascade or not built there: a coarser one may know
        // Within a quarter of the band (half a brixel interval) of a surface: rebuilt depth is exact and
        // the field's trilinear distance is off by far less than that.
        atomicAdd(check.counts[d < 0.25 * blSdfTable.cascades[c].voxelSize.w ? 0 : 1], 1u);
        return;
    }
    atomicAdd(check.counts[2], 1u);
}
