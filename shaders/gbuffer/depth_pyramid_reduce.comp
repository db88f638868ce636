#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Depth pyramid, mip n + 1 from mip n: the min of the mins and the max of the maxes of the 2 × 2 texels below,
// and of a third column (row) where mip n's width (height) is odd and this is the last column (row), so every
// texel of mip n lies under one of mip n + 1 (core/gbuffer/depth_pyramid.cpp, docs/gbuffer.md).
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    uvec4 size;  // xy mip n's size, zw mip n + 1's
} params;
BL_IMAGE(0, rg32f) uniform readonly image2D source;        // mip n
BL_IMAGE(1, rg32f) uniform writeonly image2D destination;  // mip n + 1
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), params.size.zw))) return;
    ivec2 last = ivec2(params.size.xy) - 1;
    // The footprint's far corner: 2p + 1, or 2p + 2 on a last column (row) above an odd size; clamped for
    // sizes that stop halving at 1.
    ivec2 extra = ivec2(equal(p, ivec2(params.size.zw) - 1)) * (ivec2(params.size.xy) & 1);
    ivec2 hi = min(2 * p + 1 + extra, last);
    vec2 mm = vec2(1e30, -1e30);
    for (int y = 2 * p.y; y <= hi.y; ++y)
        for (int x = 2 * p.x; x <= hi.x; ++x) {
            vec2 t = imageLoad(source, ivec2(x, y)).rg;
            mm = vec2(min(mm.x, t.x), max(mm.y, t.y));
        }
    imageStore(destination, p, vec4(mm, 0.0, 0.0));
}
