#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The picture a window shows: one of the renderer's images (the final image, an AOV or a debug view) into a
// rectangle of an RGBA8 display texture, scaled by nearest neighbour (a picture-in-picture is a second
// dispatch into a smaller rectangle). Radiance is mapped exactly as image files are written
// (examples/demo_renderer/image_io.cpp: exposure, the filmic curve, sRGB), so the window shows what a PNG of
// the same frame holds.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    uvec4 rect;    // xy: the rectangle's top-left pixel in the display texture, zw: its size
    uvec4 source;  // xy: the source's size, z: how to map it (below), w: 1 = read the buffer, 0 = the texture
    vec4 map;      // x: exposure; yzw: the eye (depth mode)
} params;
BL_TEXTURE(0) uniform sampler2D sourceTexture;
BL_READ_BUFFER(0) SourceBuffer { vec4 sourceBuffer[]; };
BL_IMAGE(0, rgba8) uniform writeonly image2D display;

const uint kRadiance = 0u;  // linear radiance: exposure, filmic, sRGB
const uint kColor = 1u;     // linear colour in [0, 1] (albedo): sRGB
const uint kSigned = 2u;    // [-1, 1] (normals): x * 0.5 + 0.5
const uint kDisplay = 3u;   // already display-encoded (debug views): copied
const uint kDepth = 4u;     // world positions (w = 1 where drawn): distance to the eye as 1 / (1 + d / 4)
const uint kMotion = 5u;    // UV motion: |xy| × 20 × exposure

float filmic(float x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 toSrgb(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
    uvec2 local = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(local, params.rect.zw))) return;
    uvec2 src = min(local * params.source.xy / params.rect.zw, params.source.xy - 1u);
    vec4 v = params.source.w == 1u ? sourceBuffer[src.y * params.source.x + src.x] : texelFetch(sourceTexture, ivec2(src), 0);
    vec3 c;
    uint mode = params.source.z;
    if (mode == kRadiance) {
        vec3 x = max(v.rgb * params.map.x, vec3(0.0));
        c = toSrgb(vec3(filmic(x.r), filmic(x.g), filmic(x.b)));
    } else if (mode == kColor) {
        c = toSrgb(clamp(v.rgb, 0.0, 1.0));
    } else if (mode == kSigned) {
        c = clamp(v.rgb * 0.5 + 0.5, 0.0, 1.0);
    } else if (mode == kDepth) {
        c = vec3(v.w != 0.0 ? 1.0 / (1.0 + distance(v.xyz, params.map.yzw) / 4.0) : 0.0);
    } else if (mode == kMotion) {
        c = vec3(clamp(abs(v.xy) * 20.0 * params.map.x, 0.0, 1.0), 0.0);
    } else {
        c = v.rgb;
    }
    if (any(isnan(c))) c = vec3(1.0, 0.0, 1.0);  // never let a NaN look like black
    imageStore(display, ivec2(params.rect.xy + local), vec4(c, 1.0));
}
