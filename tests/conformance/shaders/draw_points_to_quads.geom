#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Expands each point into an axis-aligned quad of half-size `halfSize` (clip units).
layout(points) in;
layout(triangle_strip, max_vertices = 4) out;
BL_CONSTANTS(0) uniform Params { vec2 halfSize; } params;
layout(location = 0) in vec4 gColor[];
layout(location = 0) out vec4 vColor;
void main() {
    vec4 c = gl_in[0].gl_Position;
    for (int i = 0; i < 4; ++i) {
        vec2 corner = vec2(i & 1, i >> 1) * 2.0 - 1.0;
        vColor = gColor[0];
        gl_Position = vec4(c.xy + corner * params.halfSize, c.zw);
        EmitVertex();
    }
    EndPrimitive();
}
