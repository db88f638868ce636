#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Copies every texel of an unsigned-integer 2D texture into a uvec4 buffer (row-major).
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params { ivec2 size; int lod; } params;
BL_TEXTURE(0) uniform usampler2D source;
BL_STORAGE_BUFFER(0) Output { uvec4 texels[]; } outBuf;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, params.size))) return;
    outBuf.texels[p.y * params.size.x + p.x] = texelFetch(source, p, params.lod);
}
