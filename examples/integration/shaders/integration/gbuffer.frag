#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The application's G-buffer, fragment stage. What GI reads (docs/gi.md, "Input conventions"): world
// normals (stored as-is in a float target, so GI is told unpack scale 1, offset 0), roughness (alpha of the
// albedo target), UV-space motion (current - previous). Depth comes from the D32_FLOAT depth target.
layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec4 vMaterial;
layout(location = 2) in vec4 vClip;
layout(location = 3) in vec4 vPreviousClip;
layout(location = 0) out vec4 outNormal;          // RGBA16_FLOAT
layout(location = 1) out vec4 outAlbedoRoughness; // RGBA8_UNORM, linear
layout(location = 2) out vec2 outMotion;          // RG16_FLOAT
void main() {
    // The cube's outward face normal: the camera is outside every box, so the visible side is the outer one.
    outNormal = vec4(normalize(vNormal), 0.0);
    outAlbedoRoughness = vMaterial;
    vec2 uv = vClip.xy / vClip.w * 0.5 + 0.5;
    vec2 previousUv = vPreviousClip.xy / vPreviousClip.w * 0.5 + 0.5;
    outMotion = uv - previousUv;
}
