// The reflection classifier's parameters (reflections::ReflectionClassifier; core/reflections/reflection_classifier.cpp's
// Params) and the G-buffer reads its passes share, so that the screen-space trace and the SDF pass see the same
// surface: include after bricklight/bindings.glsl. Everything per frame lives in this read buffer, never in
// BL_CONSTANTS: lavapipe compiles a new shader variant for each constant value a branch depends on.
#ifndef BRICKLIGHT_CLASSIFY_REFLECTION_PARAMS_GLSL
#define BRICKLIGHT_CLASSIFY_REFLECTION_PARAMS_GLSL
BL_READ_BUFFER(0) ReflectionParams {
    mat4 inverseViewProjection;
    mat4 viewProjection;
    mat4 previousViewProjection;
    mat4 inverseProjection;  // rows 2 and 3 give a depth's view distance
    vec4 normalScale;        // xyz; w: roughness threshold (perceptual)
    vec4 normalBias;         // xyz; w: SDF roughness threshold (perceptual)
    vec4 hybrid;             // x miss weight, y spawn rate, zw motion vector scale
    uvec4 size;              // width, height, tiles along x, tiles along y
    uvec4 options;           // samples per quad, roughness channel, roughness perceptual, reversed depth
    uvec4 options2;          // use hit counter, use screen space, use SDF, has motion vectors
    uvec4 frame;             // x frame index
    uvec4 trace;             // max iterations, pyramid mips
    vec4 trace2;             // thickness (world), edge fade (screen fraction), confidence threshold
    uvec4 debug;             // x debug view mode
} params;

const uint kReflectionHelper = 0xFFFFFFFFu;

bool blReflectionIsSky(float depth) {
    return params.options.w != 0u ? !(depth > 0.0) : !(depth < 1.0);  // NaN: sky
}

// Depth with the near side small, whichever way the depth buffer runs.
float blReflectionNearSmall(float depth) {
    float flipped = 1.0 - depth;
    return params.options.w != 0u ? flipped : depth;
}

// The world position of a pixel centre's depth (NDC y −1 at the top row).
vec3 blReflectionWorldPosition(vec2 pixelCentre, float depth) {
    vec2 ndc = pixelCentre / vec2(params.size.xy) * 2.0 - 1.0;
    vec4 w = params.inverseViewProjection * vec4(ndc, depth, 1.0);
    return w.xyz / w.w;
}

// The unit vector from a surface point towards the viewer, for perspective and orthographic cameras alike: towards
// the near plane's point of the same pixel.
vec3 blReflectionToViewer(vec2 pixelCentre, vec3 worldPosition) {
    float nearDepth = params.options.w != 0u ? 1.0 : 0.0;
    return normalize(blReflectionWorldPosition(pixelCentre, nearDepth) - worldPosition);
}

// Distance along the view axis of a device depth (perspective or orthographic).
float blReflectionViewDistance(float depth) {
    mat4 m = params.inverseProjection;
    float z = m[2][2] * depth + m[3][2], w = m[2][3] * depth + m[3][3];
    return -z / w;
}

vec3 blReflectionNormal(vec4 stored) {
    return normalize(stored.xyz * params.normalScale.xyz + params.normalBias.xyz);
}

// Perceptual roughness from the roughness texture's texel.
float blReflectionRoughness(vec4 texel) {
    uint c = params.options.y;
    float v = c == 0u ? texel.x : c == 1u ? texel.y : c == 2u ? texel.z : texel.w;
    float fromAlpha = sqrt(max(v, 0.0));
    return params.options.z != 0u ? v : fromAlpha;
}

uint blReflectionPack(uvec2 pixel, uint copyFlags) { return pixel.x | (pixel.y << 15u) | (copyFlags << 29u); }
uvec2 blReflectionPixel(uint entry) { return uvec2(entry & 0x7FFFu, (entry >> 15u) & 0x3FFFu); }

// A 32-bit integer hash (a PCG output permutation): the same bits on every backend.
uint blReflectionHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
uint blReflectionHash3(uvec3 v) { return blReflectionHash(v.x ^ blReflectionHash(v.y ^ blReflectionHash(v.z))); }
// [0, 1) with 24 bits: exact in float, so the CPU can repeat the dice.
float blReflectionUnit(uint h) { return float(h >> 8u) * (1.0 / 16777216.0); }

#endif
