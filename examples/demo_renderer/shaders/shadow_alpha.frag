#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The sun's shadow maps for scenes with alpha-tested materials: the same test as gbuffer.frag (coverage = base
// alpha x the texture's alpha at level 0, against the cut-off; cut-off 0 opaque), so that light passes where
// the camera sees through. Writes depth only.
BL_READ_BUFFER(2) Materials { vec4 materials[]; };  // 4 per material (gbuffer.frag); [2].x layer, [3].xy cut-off, base alpha
BL_TEXTURE(0) uniform sampler2DArray baseColorTextures;
layout(location = 0) flat in uint vMaterial;
layout(location = 1) in vec2 vUv;
void main() {
    vec2 alphaTest = materials[4u * vMaterial + 3u].xy;
    if (alphaTest.x <= 0.0) return;
    float layer = materials[4u * vMaterial + 2u].x;
    float alpha = layer >= 0.0 ? textureLod(baseColorTextures, vec3(vUv, layer), 0.0).a : 1.0;
    if (alpha * alphaTest.y < alphaTest.x) discard;
}
