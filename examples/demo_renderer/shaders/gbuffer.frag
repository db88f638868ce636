#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// G-buffer targets: 0 albedo (rgb) + roughness, 1 world normal facing the camera (xyz), 2 emission (rgb,
// front faces only) + metalness, 3 motion vector (UV space, current - previous), 4 world position (w = 1
// where geometry was drawn; exact, so that shadow rays start on the surface). Depth: D32.
BL_CONSTANTS(0) uniform Camera {
    mat4 viewProjection;
    mat4 previousViewProjection;
    vec4 eye;
} camera;
// 4 per material: albedo, roughness; emission, metalness; layer, F0, transmission, ior; alpha cut-off, base alpha
BL_READ_BUFFER(2) Materials { vec4 materials[]; };
BL_TEXTURE(0) uniform sampler2DArray baseColorTextures;
layout(location = 0) in vec3 vNormal;
layout(location = 1) flat in uint vMaterial;
layout(location = 2) in vec4 vClip;
layout(location = 3) in vec4 vPreviousClip;
layout(location = 4) in vec3 vWorld;
layout(location = 5) in vec2 vUv;
layout(location = 6) flat in vec3 vGeometricNormal;
layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outEmission;
layout(location = 3) out vec2 outMotion;
layout(location = 4) out vec4 outPosition;
void main() {
    // The front face (counter-clockwise in the world, as the path tracer's one-sided emitters) is the side
    // its normal points to; decided from the geometry, not from the rasterizer's winding rule.
    bool front = dot(vGeometricNormal, camera.eye.xyz - vWorld) > 0.0;
    vec3 facing = front ? vGeometricNormal : -vGeometricNormal;
    vec3 shading = normalize(vNormal);  // interpolated vertex normals (the triangle's own where none)
    if (dot(shading, facing) < 0.0) shading = -shading;
    vec4 a = materials[4u * vMaterial], e = materials[4u * vMaterial + 1u];
    float layer = materials[4u * vMaterial + 2u].x;
    // Level 0, as the path tracer samples it (no derivatives there).
    vec4 texel = layer >= 0.0 ? textureLod(baseColorTextures, vec3(vUv, layer), 0.0) : vec4(1.0);
    // Alpha-tested (cut-off > 0): a texel whose coverage is below the cut-off is a hole, not a surface.
    vec2 alphaTest = materials[4u * vMaterial + 3u].xy;
    if (alphaTest.x > 0.0 && texel.a * alphaTest.y < alphaTest.x) discard;
    a.rgb *= texel.rgb;
    outAlbedo = a;
    outNormal = vec4(shading, materials[4u * vMaterial + 2u].y);  // w: dielectric specular reflectance
    outEmission = vec4(front ? e.rgb : vec3(0.0), e.a);
    vec2 uv = vClip.xy / vClip.w * 0.5 + 0.5;
    vec2 previousUv = vPreviousClip.xy / vPreviousClip.w * 0.5 + 0.5;
    outMotion = uv - previousUv;
    outPosition = vec4(vWorld, 1.0);
}
