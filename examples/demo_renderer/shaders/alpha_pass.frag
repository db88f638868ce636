#version 450
#extension GL_GOOGLE_include_directive : require
// The SDF GI's alpha pass (bricklight/alpha_pass.glsl): the G-buffer's alpha test (gbuffer.frag), base alpha ×
// the texture layer's alpha at level 0 against the cut-off, at the texture coordinates alpha_pass.vert passes.
#include "bricklight/alpha_pass.glsl"
BL_READ_BUFFER(2) Materials { vec4 materials[]; };  // 4 per material: ...; layer in [4m + 2].x; cut-off, base alpha
BL_TEXTURE(4) uniform sampler2DArray baseColorTextures;

bool blAlphaPresent(BlAlphaFragment f) {
    uint material = uint(f.user.x + 0.5);
    vec2 alphaTest = materials[4u * material + 3u].xy;
    float layer = materials[4u * material + 2u].x;
    float alpha = layer >= 0.0 ? textureLod(baseColorTextures, vec3(f.user.yz, layer), 0.0).a : 1.0;
    return alpha * alphaTest.y >= alphaTest.x;
}
