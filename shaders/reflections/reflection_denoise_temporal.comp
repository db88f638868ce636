#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The reflection denoiser's temporal pass (reflections::ReflectionDenoiser), over the listed tiles only: each pixel's
// history is found by surface motion (its world position in the previous camera), kept only where the previous
// depth there rebuilds the same point, clipped to this frame's 3×3 neighbourhood (mean ± 1.25 σ of the resolved
// samples for mirrors, wider for glossy surfaces; against ghosting), and blended with this frame's sample by sample count. Mirrors keep a short history:
// their reflections move against the surface when the camera moves.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "reflection_denoise_params.glsl"
BL_TEXTURE(0) uniform sampler2D radiance;
BL_TEXTURE(1) uniform sampler2D depthTexture;
BL_TEXTURE(2) uniform sampler2D roughnessTexture;
BL_TEXTURE(3) uniform sampler2D historyRadiance;  // the previous frame's (a = samples)
BL_TEXTURE(4) uniform sampler2D historyDepth;
BL_IMAGE(0, rgba16f) uniform writeonly image2D history;
BL_IMAGE(1, r32f) uniform writeonly image2D historyDepthOut;

void main() {
    ivec2 pixel;
    if (!blDenoisePixel(pixel)) return;
    float depth = texelFetch(depthTexture, pixel, 0).r;
    imageStore(historyDepthOut, pixel, vec4(depth));
    if (blDenoiseIsSky(depth)) {
        imageStore(history, pixel, vec4(0.0));
        return;
    }
    vec2 size = vec2(params.size.xy);
    vec4 current = texelFetch(radiance, pixel, 0);
    vec3 p = blDenoiseWorld((vec2(pixel) + 0.5) / size, depth, params.inverseViewProjection);
    float roughness = blDenoiseRoughness(texelFetch(roughnessTexture, pixel, 0));

    // This frame's neighbourhood of resolved samples.
    vec3 sum = vec3(0.0), sumSq = vec3(0.0);
    float n = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), ivec2(params.size.xy) - 1);
            vec4 s = texelFetch(radiance, q, 0);
            if (s.a <= 0.0) continue;
            sum += s.rgb;
            sumSq += s.rgb * s.rgb;
            n += 1.0;
        }

    vec4 previous = vec4(0.0);
    if ((params.size.w & 4u) != 0u) {
        vec4 clip = params.previousViewProjection * vec4(p, 1.0);
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        ivec2 q = ivec2(floor(uv * size));
        if (clip.w > 0.0 && all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, ivec2(params.size.xy)))) {
            float before = texelFetch(historyDepth, q, 0).r;
            vec3 seen = blDenoiseWorld((vec2(q) + 0.5) / size, before, params.previousInverseViewProjection);
            // The same surface: within 2 % of the distance to the camera (one pixel's footprint at grazing angles).
            if (!blDenoiseIsSky(before) && distance(seen, p) < 0.02 * distance(p, params.eye.xyz)) previous = texelFetch(historyRadiance, q, 0);
        }
    }
    if (previous.a > 0.0 && n > 0.0) {
        vec3 mean = sum / n;
        vec3 sigma = sqrt(max(sumSq / n - mean * mean, vec3(0.0)));
        // Glossy samples scatter widely about their mean: a tight box clips their history's bright tail and darkens
        // them (roughness 0.3, 1.25 σ: 5 % of the floor's light), so the box widens with roughness.
        float box = 1.25 + 2.75 * clamp(roughness / 0.3, 0.0, 1.0);
        previous.rgb = clamp(previous.rgb, mean - box * sigma, mean + box * sigma);
    }
    float most = mix(4.0, params.normalScale.w, clamp(roughness / 0.3, 0.0, 1.0));
    vec4 result;
    if (current.a <= 0.0) {
        result = previous;  // no sample this frame: the history alone (or nothing)
    } else {
        float samples = min(previous.a + 1.0, max(most, 1.0));
        result = vec4(mix(previous.rgb, current.rgb, 1.0 / samples), samples);
    }
    imageStore(history, pixel, result);
}
