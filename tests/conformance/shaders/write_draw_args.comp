#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Writes indirect draw arguments: non-indexed (vertexCount, instanceCount, firstVertex, firstInstance) at
// word 0 and indexed (indexCount, instanceCount, firstIndex, vertexOffset, firstInstance) at word 4.
layout(local_size_x = 1) in;
BL_CONSTANTS(0) uniform Params { uint vertexCount; uint instanceCount; uint indexCount; uint firstIndex; } params;
BL_STORAGE_BUFFER(0) Args { uint words[]; } args;
void main() {
    args.words[0] = params.vertexCount; args.words[1] = params.instanceCount; args.words[2] = 0u; args.words[3] = 0u;
    args.words[4] = params.indexCount; args.words[5] = params.instanceCount; args.words[6] = params.firstIndex;
    args.words[7] = 0u; args.words[8] = 0u;
}
