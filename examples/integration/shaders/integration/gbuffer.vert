#version 450
#extension GL_GOOGLE_include_directive : require
// The bricklight/ folder is on the include path of every shader built with bricklight_add_shaders().
#include "bricklight/bindings.glsl"
// The application's G-buffer, vertex stage: one unit cube drawn once per box (instanced), each instance
// with its own transform and material.
BL_CONSTANTS(0) uniform Camera {
    mat4 viewProjection;          // projection with y flipped: clip y = -1 is image row 0 (the top)
    mat4 previousViewProjection;  // last frame's, for motion vectors
} camera;
layout(location = 0) in vec3 position;      // per vertex: the unit cube
layout(location = 1) in vec3 normal;
layout(location = 2) in vec4 modelRow0;     // per instance: the affine transform's three rows
layout(location = 3) in vec4 modelRow1;
layout(location = 4) in vec4 modelRow2;
layout(location = 5) in vec4 material;      // per instance: albedo, roughness
layout(location = 0) out vec3 vNormal;
layout(location = 1) out vec4 vMaterial;
layout(location = 2) out vec4 vClip;
layout(location = 3) out vec4 vPreviousClip;
void main() {
    mat4 model = transpose(mat4(modelRow0, modelRow1, modelRow2, vec4(0.0, 0.0, 0.0, 1.0)));
    vec4 world = model * vec4(position, 1.0);
    vNormal = transpose(inverse(mat3(model))) * normal;  // correct under non-uniform scale
    vMaterial = material;
    vClip = camera.viewProjection * world;
    vPreviousClip = camera.previousViewProjection * world;  // the room is static: only the camera moves
    gl_Position = vClip;
}
