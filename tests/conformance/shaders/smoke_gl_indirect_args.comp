#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// GL smoke test: writes DispatchIndirectArgs {groups, 1, 1} for a later dispatchIndirect.
layout(local_size_x = 1) in;
BL_CONSTANTS(0) uniform Params {
    uint groups;
} params;
BL_STORAGE_BUFFER(0) Args {
    uint x, y, z;
} args;
void main() {
    args.x = params.groups;
    args.y = 1u;
    args.z = 1u;
}
