#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Passes 1 and 2 in one: the application's G-buffer at internal resolution, in our own encoding
// (gi_input.glsl: device depth, normal + perceptual roughness packed; UV motion), and the disocclusion
// mask from this pixel's own values, which would otherwise wait a level for them.
//
// Disocclusion: a pixel keeps last frame's history when its motion vector lands on a surface of the
// previous frame that is the same surface: its position within a small fraction of the view distance of
// the plane through this pixel, and its normal within ~25 degrees.
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D inputDepth;
BL_TEXTURE(1) uniform sampler2D inputNormals;
BL_TEXTURE(2) uniform sampler2D inputRoughness;
BL_TEXTURE(3) uniform sampler2D inputMotion;
BL_TEXTURE(4) uniform sampler2D depthBefore;
BL_TEXTURE(5) uniform usampler2D surfaceBefore;
BL_IMAGE(0, r32f) uniform writeonly image2D outDepth;
BL_IMAGE(1, r32ui) uniform writeonly uimage2D outSurface;
BL_IMAGE(2, rg16f) uniform writeonly image2D outMotion;
BL_IMAGE(3, r8) uniform writeonly image2D disocclusion;  // 1 = history valid
#include "gi_input.glsl"

bool giHistoryValid(uvec2 pixel, float depth, uint surface, vec2 motion) {
    if (giIsSky(depth) || !giHasFlag(GI_FLAG_HISTORY_VALID) || giHasFlag(GI_FLAG_RESET_HISTORY)) return false;
    vec2 uv = giPixelUv(pixel);
    vec2 previousUv = uv - motion;
    if (!(all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThan(previousUv, vec2(1.0))))) return false;  // NaN too
    ivec2 previousPixel = ivec2(previousUv * vec2(giFrame.size.xy));
    float previousDepth = texelFetch(depthBefore, previousPixel, 0).r;
    if (giIsSky(previousDepth)) return false;
    vec3 p = giWorldPosition(uv, depth, giCamera.inverseViewProjection);
    vec3 q = giWorldPosition((vec2(previousPixel) + 0.5) / vec2(giFrame.size.xy), previousDepth,
                             giCamera.previousInverseViewProjection);
    vec3 n = giSurfaceNormal(surface);
    vec3 m = giSurfaceNormal(texelFetch(surfaceBefore, previousPixel, 0).r);
    float distance = length(p - giFrame.camera.xyz);
    float plane = abs(dot(q - p, n));
    // One pixel's footprint on a slanted surface can put the neighbour's centre this far off.
    float pixelSize = 2.0 * distance / float(giFrame.size.y);
    return plane < 0.01 * distance + 2.0 * pixelSize && dot(n, m) > 0.9;
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, giFrame.size.xy))) return;
    float depth;
    uint surface;
    giReadInput(pixel, depth, surface);
    // The flag is combined with per-pixel data or selected on, never alone in a branch condition: lavapipe
    // compiles (and leaks) a new variant per dispatch for branches on constants only (docs/notes/soak.md).
    // So the motion vectors are always fetched: without them (camera motion), texel (0, 0) of the 1×1
    // stand-in bound there, unused.
    bool cameraMotion = giHasFlag(GI_FLAG_CAMERA_MOTION);
    ivec2 source = giInputPixel(pixel);
    ivec2 origin = ivec2(0);
    ivec2 motionTexel = cameraMotion ? origin : source;
    vec2 given = texelFetch(inputMotion, motionTexel, 0).xy * giFrame.motion.xy;
    vec2 fromCamera = vec2(0.0);
    if (cameraMotion && !giIsSky(depth)) {
        // No motion vectors: where this point of a still world was on last frame's screen.
        vec2 uv = giPixelUv(pixel);
        vec4 before = giCamera.previousViewProjection * vec4(giWorldPosition(uv, depth, giCamera.inverseViewProjection), 1.0);
        if (before.w > 0.0) fromCamera = uv - (before.xy / before.w * 0.5 + 0.5);
    }
    vec2 motion = cameraMotion ? fromCamera : given;
    if (!(giFinite(motion.x) && giFinite(motion.y))) motion = vec2(0.0);
    // The stored motion is what the reprojections read: rg16f rounds it, and the mask must agree with them.
    motion = unpackHalf2x16(packHalf2x16(motion));
    imageStore(outDepth, ivec2(pixel), vec4(depth));
    imageStore(outSurface, ivec2(pixel), uvec4(surface));
    imageStore(outMotion, ivec2(pixel), vec4(motion, 0.0, 0.0));
    imageStore(disocclusion, ivec2(pixel), vec4(giHistoryValid(pixel, depth, surface, motion) ? 1.0 : 0.0));
}
