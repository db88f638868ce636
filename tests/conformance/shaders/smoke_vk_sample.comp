#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Vulkan smoke test: samples a texture at texel centres (nearest sampler) and packs RGBA8 into uints.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    uvec2 size;
} params;
BL_TEXTURE(0) uniform sampler2D tex;
BL_STORAGE_BUFFER(0) Output {
    uint texels[];
} outBuf;
void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(p, params.size))) return;
    vec4 c = textureLod(tex, (vec2(p) + 0.5) / vec2(params.size), 0.0);
    outBuf.texels[p.y * params.size.x + p.x] = packUnorm4x8(c);
}
