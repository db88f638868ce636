#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Blends the triangle's colour over the computed pattern, sampled from the texture the compute pass wrote.
BL_CONSTANTS(0) uniform Params { vec2 invSize; } params;
BL_TEXTURE(0) uniform sampler2D pattern;
layout(location = 0) in vec3 vColor;
layout(location = 0) out vec4 outColor;
void main() {
    vec3 background = texture(pattern, gl_FragCoord.xy * params.invSize).rgb;
    outColor = vec4(mix(background, vColor, 0.75), 1.0);
}
