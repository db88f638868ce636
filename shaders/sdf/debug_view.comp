#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
// Debug view: one primary ray per pixel through the field, coloured by distance, normal, iteration count
// (heat map), brick id, cascade id or brick-local position; optionally with the edges of the cascades'
// and instances' boxes drawn over it.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    mat4 inverseViewProjection;
    vec4 eye;        // xyz: camera position (w unused)
    uvec4 size;      // xy: output size, z: mode, w: number of overlay boxes
    uvec4 cascades;  // x: start, y: end
    vec4 range;      // x: tMin, y: tMax
} params;
BL_READ_BUFFER(0) Overlays { vec4 overlayBoxes[]; };  // min.xyz + colour index, max.xyz
BL_IMAGE(0, rgba8) uniform writeonly image2D outputImage;

vec3 heat(float x) {
    x = clamp(x, 0.0, 1.0);
    return clamp(vec3(1.5 - abs(4.0 * x - 3.0), 1.5 - abs(4.0 * x - 2.0), 1.5 - abs(4.0 * x - 1.0)), 0.0, 1.0);
}

vec3 hashColour(uint v) {
    v ^= v >> 16; v *= 0x7feb352du; v ^= v >> 15; v *= 0x846ca68bu; v ^= v >> 16;
    return vec3(uvec3(v, v >> 8, v >> 16) & 255u) / 255.0 * 0.8 + 0.2;
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(params.size.xy) * 2.0 - 1.0;
    ndc.y = -ndc.y;  // image origin top-left
    vec4 farPoint = params.inverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec4 nearPoint = params.inverseViewProjection * vec4(ndc, 0.0, 1.0);
    vec3 origin = params.eye.xyz;
    vec3 direction = normalize(farPoint.xyz / farPoint.w - nearPoint.xyz / nearPoint.w);
    BlSdfRay ray = blSdfMakeRay(origin, direction, params.range.x, params.range.y);
    ray.startCascade = params.cascades.x;
    ray.endCascade = params.cascades.y;
    BlSdfHit hit = blSdfTrace(ray);
    vec3 colour = vec3(0.05, 0.05, 0.08);
    uint mode = params.size.z;
    if (mode == 2u) {
        colour = heat(float(hit.iterations) / 128.0);
    } else if (hit.hit) {
        if (mode == 0u) colour = vec3(1.0 - clamp(hit.t / max(1e-6, 0.25 * length(vec3(blSdfTable.cascades[blSdfTable.header.x - 1u].voxelSize.x) * 64.0)), 0.0, 1.0));
        else if (mode == 1u) colour = hit.normal * 0.5 + 0.5;
        else if (mode == 3u) colour = hashColour(hit.brickId);
        else if (mode == 4u) colour = hashColour(hit.cascade + 977u);
        else colour = hit.brickUvw;
    }
    // Box edges: where the ray enters a box (before the hit) close to two of its faces.
    vec3 invD = 1.0 / mix(direction, vec3(1e-20), lessThan(abs(direction), vec3(1e-20)));
    for (uint i = 0u; i < params.size.w; ++i) {
        vec3 lo = overlayBoxes[2u * i].xyz, hi = overlayBoxes[2u * i + 1u].xyz;
        vec2 span = blSdfRayBox(origin, invD, lo, hi);
        if (span.x > span.y || span.y < 0.0) continue;
        float tEdge = span.x > 0.0 ? span.x : span.y;
        if (hit.hit && tEdge > hit.t) continue;
        vec3 p = origin + direction * tEdge;
        float width = 0.004 * tEdge + 1e-4 * length(hi - lo);
        vec3 near = min(abs(p - lo), abs(p - hi));
        int close = int(near.x < width) + int(near.y < width) + int(near.z < width);
        if (close >= 2) colour = mix(colour, hashColour(uint(overlayBoxes[2u * i].w) + 31u), 0.85);
    }
    imageStore(outputImage, ivec2(pixel), vec4(colour, 1.0));
}
