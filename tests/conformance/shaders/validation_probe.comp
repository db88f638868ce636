#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Declares one binding of every class so the validation tests can omit, misplace or misuse each one.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    vec4 scale;
} params;
BL_TEXTURE(0) uniform sampler2D source;
BL_READ_BUFFER(0) Weights {
    float weights[];
} weightsBuf;
BL_STORAGE_BUFFER(0) Counters {
    uint counters[];
} countersBuf;
BL_IMAGE(0, rgba16f) uniform image2D target;
// Declared and never used (as a shared include declares a set that a shader uses in part): the compiler
// drops it, and a record may still bind it.
BL_READ_BUFFER(3) Unused {
    float unused[];
} unusedBuf;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    vec4 c = texelFetch(source, p, 0) * params.scale * weightsBuf.weights[0];
    imageStore(target, p, c);
    atomicAdd(countersBuf.counters[0], 1u);
}
