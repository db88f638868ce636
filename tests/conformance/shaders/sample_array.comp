#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Fetches texel (x, y) of every layer of a 2D array view into a vec4 buffer, layer-major.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Params { ivec4 size; } params;
BL_TEXTURE(0) uniform sampler2DArray source;
BL_STORAGE_BUFFER(0) Output { vec4 texels[]; } outBuf;
void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, params.size.xyz))) return;
    outBuf.texels[(p.z * params.size.y + p.y) * params.size.x + p.x] = texelFetch(source, p, 0);
}
