#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 2: which pixels may use last frame's history. A pixel keeps it when its motion vector lands on a
// surface of the previous frame that is the same surface: its position within a small fraction of the
// view distance of the plane through this pixel, and its normal within ~25 degrees.
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D depthNow;
BL_TEXTURE(1) uniform usampler2D surfaceNow;
BL_TEXTURE(2) uniform sampler2D motionNow;
BL_TEXTURE(3) uniform sampler2D depthBefore;
BL_TEXTURE(4) uniform usampler2D surfaceBefore;
BL_IMAGE(0, r8) uniform writeonly image2D disocclusion;  // 1 = history valid

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, giFrame.size.xy))) return;
    float keep = 0.0;
    float depth = texelFetch(depthNow, ivec2(pixel), 0).r;
    if (!giIsSky(depth) && giHasFlag(GI_FLAG_HISTORY_VALID) && !giHasFlag(GI_FLAG_RESET_HISTORY)) {
        vec2 uv = giPixelUv(pixel);
        vec2 previousUv = uv - texelFetch(motionNow, ivec2(pixel), 0).xy;
        if (all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThan(previousUv, vec2(1.0)))) {
            ivec2 previousPixel = ivec2(previousUv * vec2(giFrame.size.xy));
            float previousDepth = texelFetch(depthBefore, previousPixel, 0).r;
            if (!giIsSky(previousDepth)) {
                vec3 p = giWorldPosition(uv, depth, giCamera.inverseViewProjection);
                vec3 q = giWorldPosition((vec2(previousPixel) + 0.5) / vec2(giFrame.size.xy), previousDepth,
                                         giCamera.previousInverseViewProjection);
                vec3 n = giSurfaceNormal(texelFetch(surfaceNow, ivec2(pixel), 0).r);
                vec3 m = giSurfaceNormal(texelFetch(surfaceBefore, previousPixel, 0).r);
                float distance = length(p - giFrame.camera.xyz);
                float plane = abs(dot(q - p, n));
                // One pixel's footprint on a slanted surface can put the neighbour's centre this far off.
                float pixelSize = 2.0 * distance / float(giFrame.size.y);
                if (plane < 0.01 * distance + 2.0 * pixelSize && dot(n, m) > 0.9) keep = 1.0;
            }
        }
    }
    imageStore(disocclusion, ivec2(pixel), vec4(keep));
}
