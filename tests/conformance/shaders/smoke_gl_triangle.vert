#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// GL smoke test: position straight to clip space, colour passed through.
layout(location = 0) in vec3 position;
layout(location = 1) in vec4 color;
layout(location = 0) out vec4 vColor;
void main() {
    vColor = color;
    gl_Position = vec4(position, 1.0);
}
