#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// hello_rhi's draw: a triangle with a colour per vertex.
layout(location = 0) in vec2 position;
layout(location = 1) in vec3 color;
layout(location = 0) out vec3 vColor;
void main() {
    vColor = color;
    gl_Position = vec4(position, 0.0, 1.0);
}
