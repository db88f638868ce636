#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Zeroes an RGBA16F storage image: the reflection passes' per-frame clears. A transfer clear (clearTexture) costs
// two layout transitions per image on a GPU, far more than this pass's writes of the same bytes.
layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;
BL_IMAGE(0, rgba16f) uniform writeonly image2D target;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(p, imageSize(target)))) imageStore(target, p, vec4(0.0));
}
