#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Depth pyramid, mip 0: each pixel's depth as (min, max) = (depth, depth). (core/gbuffer/depth_pyramid.cpp)
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    uvec4 size;  // xy the depth texture's size
} params;
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_IMAGE(0, rg32f) uniform writeonly image2D pyramid;  // mip 0
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(p), params.size.xy))) return;
    float d = texelFetch(depthTexture, p, 0).r;
    imageStore(pyramid, p, vec4(d, d, 0.0, 0.0));
}
