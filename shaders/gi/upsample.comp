#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 17: internal resolution to the display outputs, joint-bilaterally: the 2×2 internal pixels around
// each display pixel weigh bilinearly, by depth similarity and by normal similarity with the display
// pixel's own G-buffer, so GI does not bleed across edges. At native resolution it is a copy. Writes
// rgb with alpha 1 (0 on sky).
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D diffuseIn;
BL_TEXTURE(1) uniform sampler2D specularIn;
BL_TEXTURE(2) uniform sampler2D depthNow;
BL_TEXTURE(3) uniform usampler2D surfaceNow;
BL_TEXTURE(4) uniform sampler2D displayDepth;
BL_TEXTURE(5) uniform sampler2D displayNormals;
BL_IMAGE(0, rgba16f) uniform writeonly image2D diffuseOut;
BL_IMAGE(1, rgba16f) uniform writeonly image2D specularOut;
BL_CONSTANTS(2) uniform Pass { uvec4 options; } pass;  // x: write specular

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, giFrame.size.zw))) return;
    float depth = texelFetch(displayDepth, ivec2(pixel), 0).r;
    vec3 n = texelFetch(displayNormals, ivec2(pixel), 0).xyz * giFrame.normalScale.xyz + giFrame.normalOffset.xyz;
    vec4 d = vec4(0.0), s = vec4(0.0);
    if (!giIsSky(depth) && giFinite(depth) && giFinite(n) && length(n) > 1e-3) {
        n = normalize(n);
        vec2 uv = (vec2(pixel) + 0.5) / vec2(giFrame.size.zw);
        vec3 p = giWorldPosition(uv, depth, giCamera.inverseViewProjection);
        float distance = length(p - giFrame.camera.xyz);
        vec2 f = uv * vec2(giFrame.size.xy) - 0.5;
        ivec2 i0 = ivec2(floor(f));
        vec2 w2 = f - vec2(i0);
        vec3 dsum = vec3(0.0), ssum = vec3(0.0);
        float total = 0.0, best = -1.0;
        vec3 bestD = vec3(0.0), bestS = vec3(0.0);
        for (int k = 0; k < 4; ++k) {
            ivec2 o = ivec2(k & 1, k >> 1);
            ivec2 q = clamp(i0 + o, ivec2(0), ivec2(giFrame.size.xy) - 1);
            float dq = texelFetch(depthNow, q, 0).r;
            if (giIsSky(dq)) continue;
            vec3 pq = giWorldPosition(giPixelUv(uvec2(q)), dq, giCamera.inverseViewProjection);
            float plane = abs(dot(pq - p, n)) / (0.01 * distance + 1e-6);
            float similarity = exp(-plane * plane) * pow(max(dot(n, giSurfaceNormal(texelFetch(surfaceNow, q, 0).r)), 0.0), 8.0);
            vec2 b = mix(1.0 - w2, w2, vec2(o));
            float w = b.x * b.y * similarity;
            vec3 dv = texelFetch(diffuseIn, q, 0).rgb, sv = texelFetch(specularIn, q, 0).rgb;
            dsum += dv * w;
            ssum += sv * w;
            total += w;
            if (similarity > best) {
                best = similarity;
                bestD = dv;
                bestS = sv;
            }
        }
        if (total > 1e-4) {
            d = vec4(dsum / total, 1.0);
            s = vec4(ssum / total, 1.0);
        } else if (best >= 0.0) {
            d = vec4(bestD, 1.0);
            s = vec4(bestS, 1.0);
        }
    }
    imageStore(diffuseOut, ivec2(pixel), d);
    if (pass.options.x != 0u) imageStore(specularOut, ivec2(pixel), s);
}
