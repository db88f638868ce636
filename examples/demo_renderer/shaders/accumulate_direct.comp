#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Temporal accumulation of the direct light (docs/render.md, "Direct light over frames"). Each frame's direct light
// is an unbiased estimate with a few emitter samples per pixel; averaging the frames a surface point has been seen
// in converges it, as rendering more samples would. The history is reprojected through the motion vectors and
// kept only where it belongs to the same surface point: the point the previous frame saw there lies within 1.5
// pixels' footprint of this one and faces the same way. Its weight is a running mean of at most size.z frames,
// lowered per pixel where the light there may have changed since:
//  - the view direction turned by more than the BRDF's specular lobe is wide (a glossy highlight moves with the
//    eye; a Lambertian surface's direct light does not depend on the view at all), and
//  - the host's cap (constants.w): lights changed (history dropped) or geometry moved (shadows move; a short mean).
// Reads buffer 0 (this frame's direct light), buffers 1, 2 (the previous frame's accumulated light, rgb + frames,
// and its surface points: xyz float bits, w the normal as snorm8, 0 where none); writes storage 0 (the accumulated light, which
// the composite and the direct-light AOV read), storage 1, 2 (this frame's history for the next).
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    vec4 eye;          // xyz this frame's eye
    vec4 previousEye;  // xyz the previous frame's eye
    uvec4 size;        // xy image size, z frames at most in the mean, w 1: the history holds a previous frame
    vec4 pixelAngle;   // x: a pixel's height at distance 1 from the eye (2 tan(fov / 2) / height)
} params;
BL_TEXTURE(0) uniform sampler2D gAlbedo;    // a roughness
BL_TEXTURE(1) uniform sampler2D gNormal;    // xyz normal, w dielectric F0
BL_TEXTURE(2) uniform sampler2D gEmission;  // a metalness
BL_TEXTURE(3) uniform sampler2D gPosition;  // w = 1 where geometry was drawn
BL_TEXTURE(4) uniform sampler2D gMotion;    // UV motion, current - previous
BL_READ_BUFFER(0) Frame { vec4 frameLight[]; };
BL_READ_BUFFER(1) PreviousLight { vec4 previousLight[]; };
BL_READ_BUFFER(2) PreviousPoint { uvec4 previousPoint[]; };
BL_STORAGE_BUFFER(0) Accumulated { vec4 accumulated[]; };
BL_STORAGE_BUFFER(1) HistoryLight { vec4 historyLight[]; };
BL_STORAGE_BUFFER(2) HistoryPoint { uvec4 historyPoint[]; };

// The BRDF's specular lobe, in radians of view-direction change that leave a highlight where it was: GGX alpha
// (perceptual roughness squared) is about the lobe's half-width. Surfaces without a specular lobe never lose
// their history to a turning view.
float lobeWidth(float roughness, float f0, float metalness) {
    if (f0 <= 0.0 && metalness <= 0.0) return 1e30;
    return max(roughness * roughness, 1e-3);
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    uint index = pixel.y * params.size.x + pixel.x;
    vec4 position = texelFetch(gPosition, ivec2(pixel), 0);
    bool geometry = position.w != 0.0;
    vec4 normal = texelFetch(gNormal, ivec2(pixel), 0);      // w: dielectric F0
    vec4 emissive = texelFetch(gEmission, ivec2(pixel), 0);  // a: metalness
    // The mean is of the reflected light: emission is exact and would bleed across an emitter's edge.
    vec3 emission = geometry ? emissive.rgb : vec3(0.0);
    vec3 light = frameLight[index].rgb - emission;
    vec3 n = normalize(normal.xyz);
    float frames = 0.0;
    vec3 history = vec3(0.0);
    if (geometry && params.size.w != 0u) {
        vec2 uv = (vec2(pixel) + 0.5) / vec2(params.size.xy);
        vec2 previousUv = uv - texelFetch(gMotion, ivec2(pixel), 0).xy;
        // Bilinear over the four previous pixels around the reprojected point, each kept only where it saw the
        // same surface: a nearest pixel would shift the history by up to half a pixel every frame, and under a
        // steady motion those shifts add up to a visible drift.
        vec2 texel = previousUv * vec2(params.size.xy) - 0.5;
        ivec2 base = ivec2(floor(texel));
        vec2 f = texel - vec2(base);
        vec3 toEye = normalize(params.eye.xyz - position.xyz);
        // A tap's point lies within ~1.4 pixels of this one's: 1.5 pixels' footprint on the surface, stretched
        // as the surface turns from the view, is the tolerance.
        float footprint = 1.5 * length(params.eye.xyz - position.xyz) * params.pixelAngle.x / max(abs(dot(n, toEye)), 0.25);
        float weightSum = 0.0, framesSum = 0.0;
        vec3 lightSum = vec3(0.0);
        for (int tap = 0; tap < 4; ++tap) {
            ivec2 offset = ivec2(tap & 1, tap >> 1);
            ivec2 q = base + offset;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(params.size.xy)))) continue;
            float w = (offset.x == 1 ? f.x : 1.0 - f.x) * (offset.y == 1 ? f.y : 1.0 - f.y);
            uint previousIndex = uint(q.y) * params.size.x + uint(q.x);
            uvec4 point = previousPoint[previousIndex];
            bool samePoint = point.w != 0u && length(uintBitsToFloat(point.xyz) - position.xyz) <= footprint &&
                             dot(unpackSnorm4x8(point.w).xyz, n) > 0.9;
            if (!samePoint || w <= 0.0) continue;
            vec4 previous = previousLight[previousIndex];
            weightSum += w;
            lightSum += w * previous.rgb;
            framesSum += w * previous.w;
        }
        // Less than half the footprint's weight found: a disocclusion edge, start over rather than trust one tap.
        if (weightSum >= 0.5) {
            float roughness = texelFetch(gAlbedo, ivec2(pixel), 0).a;
            vec3 toPreviousEye = normalize(params.previousEye.xyz - position.xyz);
            float turn = acos(clamp(dot(toEye, toPreviousEye), -1.0, 1.0));
            // Over the mean's frames the view may turn by at most the lobe's width.
            float byView = turn > 0.0 ? max(lobeWidth(roughness, normal.w, emissive.a) / turn, 1.0) : 1e30;
            frames = min(framesSum / weightSum, min(float(params.size.z) - 1.0, byView));
            history = lightSum / weightSum;
        }
    }
    vec3 mean = history + (light - history) / (frames + 1.0);
    accumulated[index] = vec4(emission + mean, 1.0);
    historyLight[index] = vec4(mean, frames + 1.0);
    historyPoint[index] = uvec4(floatBitsToUint(position.xyz), geometry ? packSnorm4x8(vec4(n, 1.0)) : 0u);  // w 0: no surface
}
