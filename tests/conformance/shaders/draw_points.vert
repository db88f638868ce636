#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
layout(location = 0) in vec3 position;
layout(location = 1) in vec4 color;
layout(location = 0) out vec4 gColor;
void main() {
    gColor = color;
    gl_Position = vec4(position, 1.0);
}
