#version 450
#extension GL_GOOGLE_include_directive : require
// The parent's own shader: it includes the public trace API, so it compiles only if bricklight_add_shaders
// passes the installed or in-tree GLSL include folder when called from outside our tree.
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
layout(local_size_x = 64) in;
BL_STORAGE_BUFFER(0) Distances {
    float distances[];
} result;
void main() {
    result.distances[gl_GlobalInvocationID.x] = blSdfDistance(vec3(float(gl_GlobalInvocationID.x)), 0u);
}
