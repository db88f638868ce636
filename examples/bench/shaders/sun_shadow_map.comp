#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
// The classifier benchmark's sun shadow map, traced through the distance field instead of rasterized (the
// benchmark has no scene renderer): one orthographic cascade over the scene's bounds; each texel's depth is the
// first surface along the sun's direction from the map's near plane, 0 nearest the sun, 1 = nothing.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    mat4 shadowToWorld;  // (u, v, depth) in [0, 1]³ → world
    vec4 direction;      // xyz: away from the sun; w: the depth range (world units)
    uvec4 size;
} params;
BL_IMAGE(0, r32f) uniform writeonly image2D depthOut;

void main() {
    uvec2 texel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(texel, params.size.xy))) return;
    vec2 uv = (vec2(texel) + 0.5) / vec2(params.size.xy);
    vec4 start = params.shadowToWorld * vec4(uv, 0.0, 1.0);
    BlSdfHit hit = blSdfTrace(blSdfMakeRay(start.xyz / start.w, params.direction.xyz, 0.0, params.direction.w));
    imageStore(depthOut, ivec2(texel), vec4(hit.hit ? hit.t / params.direction.w : 1.0));
}
