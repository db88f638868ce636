#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// One à-trous pass of the shadow denoiser (shadows::ShadowDenoiser): dispatched indirectly on the shadow
// classifier's count buffer, 32 threads per listed tile, 8 tiles a group. A ray pixel averages 3×3 taps `step`
// pixels apart, weighted by a B-spline kernel, by the tap's distance from the pixel's plane (the same surface), by
// its normal, and by how far its visibility lies from the pixel's in units of the pixel's own uncertainty (the
// standard deviation of its temporal mean: wide while it has few frames, narrow once converged, so that a
// converged penumbra is not blurred further). Taps in unlisted tiles read the hit mask's decided answer (this pass
// writes only listed tiles). Pixels that needed no ray output their decided answer unchanged.
layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;
#include "denoise_shadows_common.glsl"
BL_CONSTANTS(0) uniform Pass { ivec4 step; } pass;  // x: the taps' spacing (only scales offsets: no branch reads it)
BL_READ_BUFFER(1) Tiles { uvec4 tiles[]; } list;
BL_READ_BUFFER(2) Counts { uint counts[8]; } count;  // [7]: the listed tiles
BL_TEXTURE(0) uniform sampler2D visibilityIn;  // the history (first pass) or the previous pass's output
BL_TEXTURE(1) uniform sampler2D history;       // mean, second moment, frames
BL_TEXTURE(2) uniform usampler2D geometry;     // depth bits, packed normal
BL_IMAGE(0, r32ui) uniform readonly uimage2D hitMask;
BL_IMAGE(1, r32ui) uniform readonly uimage2D listedTiles;
BL_IMAGE(2, r16f) uniform writeonly image2D visibilityOut;

void main() {
    uint slot = gl_LocalInvocationID.x >> 5u, lane = gl_LocalInvocationID.x & 31u;
    uint index = gl_WorkGroupID.x * 8u + slot;
    if (index >= count.counts[7]) return;
    uvec4 record = list.tiles[index];
    ivec2 tile = ivec2(record.x & 0xFFFFu, record.x >> 16u);
    ivec2 pixel = tile * ivec2(8, 4) + ivec2(lane & 7u, lane >> 3u);
    if (any(greaterThanEqual(uvec2(pixel), params.size.xy))) return;
    uvec2 g = texelFetch(geometry, pixel, 0).xy;
    float depth = uintBitsToFloat(g.x);
    float centre = texelFetch(visibilityIn, pixel, 0).x;
    if ((record.y & (1u << lane)) == 0u || blDenoiseSky(depth)) {
        imageStore(visibilityOut, pixel, vec4(blDenoiseAnswer(imageLoad(hitMask, tile).x, pixel)));
        return;
    }
    vec3 n = blDenoiseUnpackNormal(g.y);
    vec3 world = blDenoiseWorld(params.inverseViewProjection, vec2(pixel), depth);
    float tolerance = params.eye.w * length(world - params.eye.xyz);
    vec3 h = texelFetch(history, pixel, 0).xyz;
    // The temporal mean's standard deviation: the samples' variance over the frames they span.
    float sigma = sqrt(max(h.y - h.x * h.x, 0.0) / max(h.z, 1.0));
    float sum = 0.0, weights = 0.0;
    for (int k = 0; k < 9; ++k) {
        ivec2 o = ivec2(k % 3 - 1, k / 3 - 1);
        ivec2 q = pixel + o * pass.step.x;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), params.size.xy))) continue;
        uvec2 gq = texelFetch(geometry, q, 0).xy;
        float dq = uintBitsToFloat(gq.x);
        if (blDenoiseSky(dq)) continue;
        ivec2 tq = q / ivec2(8, 4);
        float vq = imageLoad(listedTiles, tq).x != 0u ? texelFetch(visibilityIn, q, 0).x : blDenoiseAnswer(imageLoad(hitMask, tq).x, q);
        vec3 wq = blDenoiseWorld(params.inverseViewProjection, vec2(q), dq);
        float plane = abs(dot(wq - world, n)) / max(tolerance, 1e-20);
        float kernel = (o.x == 0 ? 0.5 : 0.25) * (o.y == 0 ? 0.5 : 0.25);
        float w = kernel * exp(-plane) * pow(max(dot(blDenoiseUnpackNormal(gq.y), n), 0.0), 32.0) *
                  exp(-abs(vq - centre) / (4.0 * sigma + 1e-3));
        sum += w * vq;
        weights += w;
    }
    imageStore(visibilityOut, pixel, vec4(weights > 0.0 ? sum / weights : centre));
}
