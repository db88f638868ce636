#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Samples a texture at the fragment's normalized position (textures bound to a draw).
BL_CONSTANTS(1) uniform FragParams { vec2 invSize; } fparams;
BL_TEXTURE(0) uniform sampler2D source;
layout(location = 0) in vec4 vColor;
layout(location = 0) out vec4 outColor;
void main() { outColor = textureLod(source, gl_FragCoord.xy * fparams.invSize, 0.0) * vColor; }
