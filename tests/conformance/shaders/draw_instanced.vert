#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Per-vertex position, per-instance offset and colour (vertex buffer 1 is per instance).
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 offset;
layout(location = 2) in vec4 color;
layout(location = 0) out vec4 vColor;
void main() {
    vColor = color;
    gl_Position = vec4(position + offset, 0.5, 1.0);
}
