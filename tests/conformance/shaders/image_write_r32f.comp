#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Writes value = x + 1000 * y + layer * 1e6 + offset into every layer of an r32f 2D-array storage image.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
BL_CONSTANTS(0) uniform Params { ivec4 size; float offset; } params;
BL_IMAGE(0, r32f) uniform writeonly image2DArray target;
void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, params.size.xyz))) return;
    imageStore(target, p, vec4(float(p.x) + 1000.0 * float(p.y) + 1e6 * float(p.z) + params.offset));
}
