// The shadow denoiser's parameters and helpers (shadows::ShadowDenoiser; core/shadows/shadow_denoiser.cpp's Params),
// shared by its temporal, decided and filter passes (denoise_shadows_*.comp).
#ifndef BRICKLIGHT_CLASSIFY_DENOISE_SHADOWS_COMMON_GLSL
#define BRICKLIGHT_CLASSIFY_DENOISE_SHADOWS_COMMON_GLSL
BL_READ_BUFFER(0) Params {
    mat4 inverseViewProjection;          // this frame's
    mat4 previousViewProjection;         // last frame's
    mat4 inversePreviousViewProjection;
    vec4 eye;          // xyz this frame's camera position; w: depth tolerance (fraction of the distance from it)
    vec4 normalScale;  // xyz; w: clamp sigma
    vec4 normalBias;   // xyz; w: unused
    uvec4 size;        // width, height, tiles along x, reversed depth
    uvec4 options;     // max history, reset (1: the history is not read), 0, 0
} params;

bool blDenoiseSky(float depth) { return params.size.w != 0u ? !(depth > 0.0) : !(depth < 1.0); }

vec3 blDenoiseWorld(mat4 inverseViewProjection, vec2 pixel, float depth) {
    vec2 ndc = (pixel + 0.5) / vec2(params.size.xy) * 2.0 - 1.0;
    vec4 w = inverseViewProjection * vec4(ndc, depth, 1.0);
    return w.xyz / w.w;
}

// Octahedral normal in 2 × 16 bits.
uint blDenoisePackNormal(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z) + 1e-20;
    vec2 e = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return packUnorm2x16(e * 0.5 + 0.5);
}

vec3 blDenoiseUnpackNormal(uint bits) {
    vec2 e = unpackUnorm2x16(bits) * 2.0 - 1.0;
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    float t = max(-n.z, 0.0);
    n.xy += vec2(n.x >= 0.0 ? -t : t, n.y >= 0.0 ? -t : t);
    return normalize(n);
}

// The hit mask's answer for a pixel: 1 lit, 0 shadowed (bit y·8 + x of its tile's texel set: shadowed or unknown).
float blDenoiseAnswer(uint tileBits, ivec2 pixel) {
    uint bit = 1u << uint((pixel.y & 3) * 8 + (pixel.x & 7));
    return (tileBits & bit) != 0u ? 0.0 : 1.0;
}

#endif
