#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 10: last frame's accumulated diffuse and specular GI, moved along the motion vectors into this
// frame (bilinear), where the disocclusion mask keeps history; elsewhere zero with a sample count of 0
// (alpha holds the count).
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D motionNow;
BL_TEXTURE(1) uniform sampler2D disocclusion;
BL_TEXTURE(2) uniform sampler2D previousDiffuse;
BL_TEXTURE(3) uniform sampler2D previousSpecular;
BL_IMAGE(0, rgba16f) uniform writeonly image2D diffuse;
BL_IMAGE(1, rgba16f) uniform writeonly image2D specular;

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, giFrame.size.xy))) return;
    vec4 d = vec4(0.0), s = vec4(0.0);
    if (texelFetch(disocclusion, ivec2(pixel), 0).r > 0.5) {
        vec2 uv = giPixelUv(pixel) - texelFetch(motionNow, ivec2(pixel), 0).xy;
        d = textureLod(previousDiffuse, uv, 0.0);
        s = textureLod(previousSpecular, uv, 0.0);
        if (!(giFinite(d.rgb) && giFinite(d.a))) d = vec4(0.0);
        if (!(giFinite(s.rgb) && giFinite(s.a))) s = vec4(0.0);
    }
    imageStore(diffuse, ivec2(pixel), d);
    imageStore(specular, ivec2(pixel), s);
}
