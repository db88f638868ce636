// The sun's visibility from cascaded shadow maps (RasterOptions::shadows = ShadowMap): the cascade is chosen
// per pixel by view distance (the first whose slice holds it and whose map holds the offset point), the
// receiver is pushed along its normal by normalOffset texels, and the comparison is filtered by PCF: a box of
// (2·radius + 1)² bilinearly weighted comparisons, read with texelFetch (no comparison sampler needed).
// Points beyond the last cascade are lit. The cascades come from examples/demo_renderer/shadow_cascades.cpp.
#ifndef BRICKLIGHT_RENDER_SHADOW_SUN_GLSL
#define BRICKLIGHT_RENDER_SHADOW_SUN_GLSL

// A read buffer, not constants: lavapipe inlines constants that steer branches and loops into per-dispatch
// variants (docs/notes/soak.md), and these loops' bounds and branches read them. (A first version with these
// fields in two more uniform blocks of direct_light.comp crashed lavapipe in its worker thread; not pursued.)
BL_READ_BUFFER(7) ShadowSun {
    mat4 cascadeViewProjection[4];  // world → each cascade's clip space
    vec4 splitFar;     // view distance where each cascade ends
    vec4 texelSize;    // world units per texel of each cascade
    vec4 depthRange;   // world units from depth 0 to 1 of each cascade
    vec4 forward;      // xyz the camera's forward axis
    vec4 irradiance;   // rgb the sun's irradiance
    vec4 direction;    // xyz towards the sun
    vec4 bias;         // x normal offset (texels), y depth bias (texels), z PCF radius, w resolution
} shadowSun;
BL_TEXTURE(5) uniform sampler2D shadowMap;  // D32_FLOAT atlas: cascade c in tile (c & 1, c >> 1) of res² texels

// 1 lit .. 0 shadowed.
float sunShadowVisibility(vec3 p, vec3 n, vec3 eye) {
    float viewDistance = dot(p - eye, shadowSun.forward.xyz);
    int res = int(shadowSun.bias.w);
    int radius = int(shadowSun.bias.z);
    for (int c = 0; c < 4; ++c) {
        if (viewDistance > shadowSun.splitFar[c]) continue;
        float texel = shadowSun.texelSize[c];
        // Normal offset: more as the surface turns away from the sun, where a texel spreads over more depth.
        float cosTheta = clamp(dot(n, shadowSun.direction.xyz), 0.0, 1.0);
        vec3 q = p + n * (shadowSun.bias.x * texel * (1.0 - 0.5 * cosTheta));
        vec4 clip = shadowSun.cascadeViewProjection[c] * vec4(q, 1.0);
        vec2 coord = (clip.xy * 0.5 + 0.5) * float(res) - 0.5;  // texel space, centres at integers
        float edge = float(radius) + 1.0;
        if (any(lessThan(coord, vec2(edge - 1.0))) || any(greaterThan(coord, vec2(float(res) - edge)))) continue;
        float depth = clip.z - shadowSun.bias.y * texel / shadowSun.depthRange[c];
        vec2 f = coord - floor(coord);  // bilinear weights within the tile
        ivec2 base = ivec2(floor(coord)) + ivec2(c & 1, c >> 1) * res;
        float lit = 0.0;
        for (int j = -radius; j <= radius + 1; ++j) {
            float wy = j == -radius ? 1.0 - f.y : (j == radius + 1 ? f.y : 1.0);
            for (int i = -radius; i <= radius + 1; ++i) {
                float wx = i == -radius ? 1.0 - f.x : (i == radius + 1 ? f.x : 1.0);
                float stored = texelFetch(shadowMap, base + ivec2(i, j), 0).r;
                lit += (depth <= stored ? 1.0 : 0.0) * wx * wy;
            }
        }
        float side = float(2 * radius + 1);
        return lit / (side * side);
    }
    return 1.0;
}

#endif
