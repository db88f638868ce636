#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Samples a cube texture along directions read from a buffer.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint count; } params;
BL_TEXTURE(0) uniform samplerCube source;
BL_READ_BUFFER(0) Directions { vec4 dirs[]; } dirBuf;
BL_STORAGE_BUFFER(0) Output { vec4 values[]; } outBuf;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.count) return;
    outBuf.values[i] = textureLod(source, dirBuf.dirs[i].xyz, 0.0);
}
