#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/alpha_pass_vertex.glsl"
// The GI alpha pass test's vertex shader: world positions and texture coordinates.
layout(location = 0) in vec3 position;
layout(location = 1) in vec2 uv;
BL_ALPHA_VERTEX_OUTPUTS

void main() { blAlphaVertex(position, vec4(uv, 0.0, 0.0)); }
