#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_alpha.glsl"
#include "gi_specular.glsl"
// Pass 9: one specular ray per 4×4 tile (a pixel that rotates per frame) through the whole field; stores
// the brick it hit (GI_PRETRACE_MISS when it left the field: the environment; GI_PRETRACE_NONE when the
// tile's pixel is sky or too rough to trace). The full-resolution trace then marches only that brick.
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D depthNow;
BL_TEXTURE(1) uniform usampler2D surfaceNow;
BL_IMAGE(0, r32ui) uniform writeonly uimage2D pretrace;
#include "gi_bricks.glsl"
#define GI_PRETRACE_MISS 0xFFFFFFFEu
#define GI_PRETRACE_NONE 0xFFFFFFFFu

void main() {
    uvec2 tile = gl_GlobalInvocationID.xy;
    uvec2 tiles = (giFrame.size.xy + 3u) / 4u;
    if (any(greaterThanEqual(tile, tiles))) return;
    uint k = (giFrameIndex() * 5u + giPcg(tile.x * 433u + tile.y)) & 15u;
    uvec2 pixel = min(tile * 4u + uvec2(k & 3u, k >> 2), giFrame.size.xy - 1u);
    uint result = GI_PRETRACE_NONE;
    float depth = texelFetch(depthNow, ivec2(pixel), 0).r;
    uint surface = texelFetch(surfaceNow, ivec2(pixel), 0).r;
    if (!giIsSky(depth) && giSurfaceRoughness(surface) <= giFrame.normalScale.w) {
        vec3 p = giWorldPosition(giPixelUv(pixel), depth, giCamera.inverseViewProjection);
        vec3 n = giSurfaceNormal(surface);
        vec3 toEye = normalize(giFrame.camera.xyz - p);
        if (dot(n, toEye) < 0.0) n = -n;
        uint rng = giPcg(giPcg(pixel.y * giFrame.size.x + pixel.x) ^ giFrameIndex());
        vec3 d = giSpecularDirection(n, toEye, giSurfaceRoughness(surface), vec2(giRandom(rng), giRandom(rng)));
        float alpha = giSurfaceRoughness(surface) * giSurfaceRoughness(surface);
        BlSdfHit hit = giTraceThroughAlpha(giMakeSpecularRay(p + n * giPushOff(p, giFrame.trace.y), d, giFrame.trace.w, alpha), rng);
        // A ray that gave up leaves the tile to the SH caches (GI_PRETRACE_NONE), not to the sky.
        if (!hit.gaveUp) result = hit.hit ? hit.brickId : GI_PRETRACE_MISS;
    }
    imageStore(pretrace, ivec2(tile), uvec4(result));
}
