#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Depth-only draw of the scene's world-space triangles (GpuScene's vertex buffer) into one cascade of the sun's
// shadow map (raster_renderer_shadows.cpp): no fragment shader, the rasterizer's slope-scaled bias on.
BL_CONSTANTS(0) uniform Cascade {
    mat4 viewProjection;  // world → the cascade's clip space (orthographic, depth [0, 1] from the sun)
} cascade;
layout(location = 0) in vec3 position;
void main() {
    gl_Position = cascade.viewProjection * vec4(position, 1.0);
}
