#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Vulkan smoke test: writes DispatchIndirectArgs {groups, 1, 1} for a later dispatchIndirect.
layout(local_size_x = 1) in;
BL_CONSTANTS(0) uniform Params {
    uint groups;
} params;
BL_STORAGE_BUFFER(0) Args {
    uint args[3];
} argsBuf;
void main() {
    argsBuf.args[0] = params.groups;
    argsBuf.args[1] = 1u;
    argsBuf.args[2] = 1u;
}
