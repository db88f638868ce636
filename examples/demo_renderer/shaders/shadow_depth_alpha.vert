#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// shadow_depth.vert for scenes with alpha-tested materials: also hands the material and texture coordinates to
// shadow_alpha.frag, which leaves the cut-out texels out of the shadow map.
BL_CONSTANTS(0) uniform Cascade {
    mat4 viewProjection;  // world → the cascade's clip space (orthographic, depth [0, 1] from the sun)
} cascade;
layout(location = 0) in vec3 position;
layout(location = 2) in uint material;
layout(location = 4) in vec2 uv;
layout(location = 0) flat out uint vMaterial;
layout(location = 1) out vec2 vUv;
void main() {
    vMaterial = material;
    vUv = uv;
    gl_Position = cascade.viewProjection * vec4(position, 1.0);
}
