#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// One link of a texture dependency chain: the previous link's image is sampled, the next one written.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params { ivec2 size; float step; } params;
BL_TEXTURE(0) uniform sampler2D source;
BL_IMAGE(0, r32f) uniform writeonly image2D target;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, params.size))) return;
    imageStore(target, p, vec4(texelFetch(source, p, 0).x + params.step));
}
