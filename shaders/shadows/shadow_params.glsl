// The shadow classifier's parameters (shadows::ShadowClassifier; core/shadows/shadow_classifier.cpp's Params),
// shared by its classification, trace and resolve passes.
#ifndef BRICKLIGHT_CLASSIFY_SHADOW_PARAMS_GLSL
#define BRICKLIGHT_CLASSIFY_SHADOW_PARAMS_GLSL
BL_READ_BUFFER(0) Params {
    mat4 inverseViewProjection;
    mat4 worldToShadow[4];
    vec4 uvRect[4];
    vec4 sun;          // xyz towards the sun, w tan(half the sun's angle)
    vec4 depthRange;   // per cascade, world units from depth 0 to 1
    vec4 normalScale;  // xyz; w: blocker offset
    vec4 normalBias;   // xyz; w: ray push-off
    uvec4 size;        // width, height, tiles along x, mode (bit 0: 0 normals, 1 cascades; bit 1: mark unsure pixels)
    uvec4 options;     // cascades, taps, reject lit pixels, cascade ray interval
    uvec4 options2;    // tile cut-off, reversed depth, shadow map width, height
    vec4 trace;        // x: ray origin offset along the normal (world units), y: hit epsilon scale, z: soft rays' disc
                       // radius (tan of half the sun's angle; 0: hard), w: the frame's sample index
    vec4 trust;        // sure rays: x sure-hit, y sure-miss epsilon scale, z self clearance (brixels), w 1 on
} params;

// The world position of a pixel's depth (the library's conventions: NDC y −1 at the top row).
vec3 blShadowWorldPosition(ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(params.size.xy) * 2.0 - 1.0;
    vec4 w = params.inverseViewProjection * vec4(ndc, depth, 1.0);
    return w.xyz / w.w;
}

#endif
