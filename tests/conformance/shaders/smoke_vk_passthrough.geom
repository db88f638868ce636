#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Vulkan smoke test: passes triangles through, replacing the colour with a constant.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
BL_CONSTANTS(0) uniform Params {
    vec4 color;
} params;
layout(location = 0) in vec4 vColorIn[];
layout(location = 0) out vec4 vColor;
void main() {
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        vColor = params.color;
        EmitVertex();
    }
    EndPrimitive();
}
