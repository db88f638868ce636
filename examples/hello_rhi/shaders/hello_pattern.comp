#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// hello_rhi's compute pass: a smooth colour field written into a storage image.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params { ivec2 size; float time; } params;
BL_IMAGE(0, rgba8) uniform writeonly image2D target;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, params.size))) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(params.size);
    float r = 0.5 + 0.5 * sin(uv.x * 12.0 + params.time);
    float g = 0.5 + 0.5 * sin(uv.y * 9.0 + 2.0 * params.time);
    float b = 0.5 + 0.5 * sin((uv.x + uv.y) * 7.0);
    imageStore(target, p, vec4(r, g, b, 1.0) * 0.6);
}
