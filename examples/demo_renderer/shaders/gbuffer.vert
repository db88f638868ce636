#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// G-buffer: world-space triangles (GpuScene's vertex buffer) through the camera; the previous frame's
// view-projection gives the motion vector.
BL_CONSTANTS(0) uniform Camera {
    mat4 viewProjection;          // clip-space y down: row 0 of the targets is the top of the image
    mat4 previousViewProjection;
    vec4 eye;
} camera;
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uint material;
layout(location = 3) in vec3 previousPosition;  // the same vertex one frame earlier (animated scenes)
layout(location = 4) in vec2 uv;
layout(location = 5) in vec3 geometricNormal;
layout(location = 0) out vec3 vNormal;
layout(location = 1) flat out uint vMaterial;
layout(location = 2) out vec4 vClip;
layout(location = 3) out vec4 vPreviousClip;
layout(location = 4) out vec3 vWorld;
layout(location = 5) out vec2 vUv;
layout(location = 6) flat out vec3 vGeometricNormal;
void main() {
    vNormal = normal;
    vWorld = position;
    vUv = uv;
    vGeometricNormal = geometricNormal;
    vMaterial = material;
    vClip = camera.viewProjection * vec4(position, 1.0);
    vPreviousClip = camera.previousViewProjection * vec4(previousPosition, 1.0);
    gl_Position = vClip;
}
