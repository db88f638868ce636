#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// A triangle covering the viewport, from the vertex index alone, at the depth given in constants.
BL_CONSTANTS(0) uniform Params { vec4 color; float depth; } params;
layout(location = 0) out vec4 vColor;
void main() {
    vec2 p = vec2((BL_VERTEX_INDEX << 1) & 2, BL_VERTEX_INDEX & 2);
    vColor = params.color;
    gl_Position = vec4(p * 2.0 - 1.0, params.depth, 1.0);
}
