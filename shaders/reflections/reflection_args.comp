#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The reflection classifier's dispatch arguments from its counts (one thread, after the classification and again
// after the screen-space trace has appended its misses): byte 0 the screen-space trace (32 entries a group), byte
// 12 the SDF trace (64 rays a group), byte 24 the denoiser (one group per listed tile).
layout(local_size_x = 1, local_size_y = 1, local_size_z = 1) in;
BL_STORAGE_BUFFER(0) Counts { uint counts[24]; } count;
void main() {
    count.counts[0] = count.counts[9] / 32u;
    count.counts[3] = (count.counts[11] + 63u) / 64u;
    count.counts[6] = count.counts[12];
    count.counts[1] = 1u;
    count.counts[2] = 1u;
    count.counts[4] = 1u;
    count.counts[5] = 1u;
    count.counts[7] = 1u;
    count.counts[8] = 1u;
}
