#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The reflection denoiser's spatial pass (reflections::ReflectionDenoiser), over the listed tiles only: an edge-aware
// 3×3 filter of the accumulated history whose taps spread with roughness (a mirror keeps its own pixel, a glossy
// surface averages over up to 4 pixels each way), weighted by depth and normal agreement so that
// reflections do not bleed across edges. Pixels without any sample get weight 0 (the composite keeps the GI's).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "reflection_denoise_params.glsl"
BL_TEXTURE(0) uniform sampler2D history;
BL_TEXTURE(1) uniform sampler2D depthTexture;
BL_TEXTURE(2) uniform sampler2D normalTexture;
BL_TEXTURE(3) uniform sampler2D roughnessTexture;
BL_IMAGE(0, rgba16f) uniform writeonly image2D outputImage;

void main() {
    ivec2 pixel;
    if (!blDenoisePixel(pixel)) return;
    float depth = texelFetch(depthTexture, pixel, 0).r;
    vec4 centre = texelFetch(history, pixel, 0);
    if (blDenoiseIsSky(depth)) {
        imageStore(outputImage, pixel, vec4(0.0));
        return;
    }
    vec2 size = vec2(params.size.xy);
    vec3 p = blDenoiseWorld((vec2(pixel) + 0.5) / size, depth, params.inverseViewProjection);
    float distanceToEye = distance(p, params.eye.xyz);
    vec3 n = normalize(texelFetch(normalTexture, pixel, 0).xyz * params.normalScale.xyz + params.normalOffset.xyz);
    float roughness = blDenoiseRoughness(texelFetch(roughnessTexture, pixel, 0));
    // 3×3 taps (9: the pass runs on nearly every glossy pixel) spaced by roughness: 0 for mirrors (the pixel alone),
    // up to 4 pixels (a 9×9 footprint) from roughness 0.5.
    int step = int(floor(clamp(roughness * 8.0, 0.0, 4.0)));
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            if (step == 0 && (dx != 0 || dy != 0)) continue;
            ivec2 q = pixel + ivec2(dx, dy) * step;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(params.size.xy)))) continue;
            vec4 s = texelFetch(history, q, 0);
            if (s.a <= 0.0) continue;
            float dq = texelFetch(depthTexture, q, 0).r;
            if (blDenoiseIsSky(dq)) continue;
            vec3 pq = blDenoiseWorld((vec2(q) + 0.5) / size, dq, params.inverseViewProjection);
            vec3 nq = normalize(texelFetch(normalTexture, q, 0).xyz * params.normalScale.xyz + params.normalOffset.xyz);
            float plane = abs(dot(pq - p, n)) / (0.01 * distanceToEye);  // off the centre's plane, in 1 % of the distance
            float w = exp(-0.5 * float(dx * dx + dy * dy)) * exp(-plane * plane) * pow(max(dot(n, nq), 0.0), 32.0) * min(s.a, 4.0);
            sum += s.rgb * w;
            weight += w;
        }
    imageStore(outputImage, pixel, weight > 0.0 ? vec4(sum / weight, 1.0) : vec4(0.0));
}
