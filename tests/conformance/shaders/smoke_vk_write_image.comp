#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Vulkan smoke test: writes a coordinate pattern into an RGBA8 storage image.
layout(local_size_x = 8, local_size_y = 8) in;
BL_IMAGE(0, rgba8) uniform writeonly image2D outImage;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(outImage)))) return;
    imageStore(outImage, p, vec4(float(p.x) / 255.0, float(p.y) / 255.0, float(p.x + p.y) / 255.0, 1.0));
}
