#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Counts invocations and records gl_NumWorkGroups, so an indirect dispatch's size can be checked.
layout(local_size_x = 4, local_size_y = 2, local_size_z = 1) in;
BL_STORAGE_BUFFER(0) Result { uint invocations; uint numGroups[3]; uint marks[]; } result;
void main() {
    atomicAdd(result.invocations, 1u);
    if (gl_LocalInvocationIndex == 0u) {
        result.numGroups[0] = gl_NumWorkGroups.x;
        result.numGroups[1] = gl_NumWorkGroups.y;
        result.numGroups[2] = gl_NumWorkGroups.z;
        uint g = (gl_WorkGroupID.z * gl_NumWorkGroups.y + gl_WorkGroupID.y) * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        result.marks[g] = g + 1u;
    }
}
