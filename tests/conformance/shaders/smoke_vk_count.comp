#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Vulkan smoke test: every invocation adds 1 to a counter (atomics) and copies a read buffer's value.
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) Input {
    uint addend;
} inBuf;
BL_STORAGE_BUFFER(0) Counter {
    uint count;
} counter;
void main() {
    atomicAdd(counter.count, inBuf.addend);
}
