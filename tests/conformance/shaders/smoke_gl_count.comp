#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// GL smoke test: every invocation adds 1 to a counter (order-independent writers).
layout(local_size_x = 64) in;
BL_STORAGE_BUFFER(0) Counter {
    uint count;
} counter;
void main() {
    atomicAdd(counter.count, 1u);
}
