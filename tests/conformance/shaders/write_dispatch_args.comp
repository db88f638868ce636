#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Writes indirect dispatch arguments (x, y, z) at `offset` words of an args buffer.
layout(local_size_x = 1) in;
BL_CONSTANTS(0) uniform Params { uvec3 groups; uint offset; } params;
BL_STORAGE_BUFFER(0) Args { uint words[]; } args;
void main() {
    args.words[params.offset + 0u] = params.groups.x;
    args.words[params.offset + 1u] = params.groups.y;
    args.words[params.offset + 2u] = params.groups.z;
}
