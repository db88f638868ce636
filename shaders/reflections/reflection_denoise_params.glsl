// The reflection denoiser's parameters (reflections::ReflectionDenoiser; core/reflections/reflection_denoiser.cpp's
// Params) and what both of its passes compute from them.
#ifndef BRICKLIGHT_CLASSIFY_REFLECTION_DENOISE_PARAMS_GLSL
#define BRICKLIGHT_CLASSIFY_REFLECTION_DENOISE_PARAMS_GLSL
BL_READ_BUFFER(0) Params {
    mat4 inverseViewProjection;
    mat4 previousViewProjection;
    mat4 previousInverseViewProjection;
    vec4 eye;           // xyz the camera's position
    vec4 normalScale;   // xyz; w: most frames of history
    vec4 normalOffset;  // xyz
    uvec4 size;         // width, height, roughness channel, flags (1 perceptual, 2 reversed depth, 4 history valid)
    uvec4 list;         // x: the word of the count buffer that holds the listed tiles
} params;
BL_READ_BUFFER(1) Tiles { uint tiles[]; };
BL_READ_BUFFER(2) Count { uint count[]; };

bool blDenoiseIsSky(float depth) { return (params.size.w & 2u) != 0u ? !(depth > 0.0) : !(depth < 1.0); }

vec3 blDenoiseWorld(vec2 uv, float depth, mat4 inverseViewProjection) {
    vec4 w = inverseViewProjection * vec4(uv * 2.0 - 1.0, depth, 1.0);
    return w.xyz / w.w;
}

// The pixel this thread works on (tiles listed for denoising, 8×8 threads per tile), or false past the list's end.
bool blDenoisePixel(out ivec2 pixel) {
    pixel = ivec2(0);
    uint index = gl_WorkGroupID.x;
    if (index >= count[params.list.x]) return false;
    uint tile = tiles[index];
    pixel = ivec2(tile & 0xFFFFu, tile >> 16u) + ivec2(gl_LocalInvocationID.xy);
    return all(lessThan(uvec2(pixel), params.size.xy));
}

float blDenoiseRoughness(vec4 texel) {
    float r = texel[params.size.z];
    return clamp((params.size.w & 1u) != 0u ? r : sqrt(max(r, 0.0)), 0.0, 1.0);
}

#endif
