#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// GL smoke test: copies a usampler2D into a buffer, row-major (a sampled read of an image write).
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform usampler2D source;
BL_STORAGE_BUFFER(0) Output {
    uint values[];
} outBuf;
void main() {
    ivec2 size = textureSize(source, 0);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(p, size))) outBuf.values[p.y * size.x + p.x] = texelFetch(source, p, 0).r;
}
