#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Three targets of different formats: colour, window x as float, window y as uint.
layout(location = 0) in vec4 vColor;
layout(location = 0) out vec4 outColor;
layout(location = 1) out float outX;
layout(location = 2) out uint outY;
void main() {
    outColor = vColor;
    outX = gl_FragCoord.x;
    outY = uint(gl_FragCoord.y);
}
