#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The shadow denoiser's temporal pass (shadows::ShadowDenoiser): dispatched indirectly on the shadow classifier's
// count buffer, 32 threads per listed tile, 8 tiles a group. Each ray pixel blends this frame's ray answer (one
// sample of the sun's disc) into its reprojected history: last frame's four texels around the reprojected point,
// each kept only where its stored depth lies on this pixel's plane and its normal agrees (a disocclusion otherwise),
// the blend clamped to the 7×7 neighbourhood's mean ± clampSigma·σ of this frame's answers (read from the hit
// mask's bits) so that a shadow that moved does not leave a ghost. Pixels without a ray keep the decided answer.
// Every pixel of the tile writes its history and geometry; the tile is marked listed for the next passes.
layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;
#include "denoise_shadows_common.glsl"
BL_READ_BUFFER(1) Tiles { uvec4 tiles[]; } list;
BL_READ_BUFFER(2) Counts { uint counts[8]; } count;  // [7]: the listed tiles
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_TEXTURE(1) uniform sampler2D normalTexture;
BL_TEXTURE(2) uniform sampler2D previousHistory;    // mean, second moment, frames
BL_TEXTURE(3) uniform usampler2D previousGeometry;  // depth bits, packed normal
BL_IMAGE(0, r32ui) uniform readonly uimage2D hitMask;
BL_IMAGE(1, rgba16f) uniform writeonly image2D history;
BL_IMAGE(2, rg32ui) uniform writeonly uimage2D geometry;
BL_IMAGE(3, r32ui) uniform writeonly uimage2D listedTiles;

// This frame's answers around `pixel` (a 7×7 window clipped to the screen): their mean and standard deviation.
vec2 neighbourhood(ivec2 pixel) {
    ivec2 size = ivec2(params.size.xy);
    int x0 = max(pixel.x - 3, 0), x1 = min(pixel.x + 3, size.x - 1);
    uint lit = 0u, total = 0u;
    for (int y = max(pixel.y - 3, 0); y <= min(pixel.y + 3, size.y - 1); ++y) {
        for (int tx = x0 >> 3; tx <= (x1 >> 3); ++tx) {
            uint row = (imageLoad(hitMask, ivec2(tx, y >> 2)).x >> uint((y & 3) * 8)) & 0xFFu;
            int lo = max(x0 - tx * 8, 0), hi = min(x1 - tx * 8, 7);
            uint window = ((2u << uint(hi)) - 1u) & ~((1u << uint(lo)) - 1u);
            total += uint(hi - lo + 1);
            lit += uint(hi - lo + 1) - bitCount(row & window);
        }
    }
    float mean = float(lit) / float(total);
    return vec2(mean, sqrt(max(mean - mean * mean, 0.0)));  // answers are 0 or 1: E[x²] = E[x]
}

void main() {
    uint slot = gl_LocalInvocationID.x >> 5u, lane = gl_LocalInvocationID.x & 31u;
    uint index = gl_WorkGroupID.x * 8u + slot;
    if (index >= count.counts[7]) return;
    uvec4 record = list.tiles[index];
    ivec2 tile = ivec2(record.x & 0xFFFFu, record.x >> 16u);
    if (lane == 0u) imageStore(listedTiles, tile, uvec4(1u));
    ivec2 pixel = tile * ivec2(8, 4) + ivec2(lane & 7u, lane >> 3u);
    if (any(greaterThanEqual(uvec2(pixel), params.size.xy))) return;
    float depth = texelFetch(depthTexture, pixel, 0).r;
    vec3 n = normalize(texelFetch(normalTexture, pixel, 0).xyz * params.normalScale.xyz + params.normalBias.xyz);
    imageStore(geometry, pixel, uvec4(floatBitsToUint(depth), blDenoisePackNormal(n), 0u, 0u));
    float answer = blDenoiseAnswer(imageLoad(hitMask, tile).x, pixel);
    bool ray = (record.y & (1u << lane)) != 0u && !blDenoiseSky(depth);
    if (!ray) {
        imageStore(history, pixel, vec4(answer, answer, 1.0, 0.0));
        return;
    }
    vec3 world = blDenoiseWorld(params.inverseViewProjection, vec2(pixel), depth);
    float tolerance = params.eye.w * length(world - params.eye.xyz);
    vec4 previousClip = params.previousViewProjection * vec4(world, 1.0);
    vec2 at = (previousClip.xy / previousClip.w * 0.5 + 0.5) * vec2(params.size.xy) - 0.5;  // texel centres at integers
    ivec2 base = ivec2(floor(at));
    vec2 f = at - vec2(base);
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 q = base + ivec2(k & 1, k >> 1);
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(uvec2(q), params.size.xy))) continue;
        float w = ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k >> 1) != 0 ? f.y : 1.0 - f.y);
        uvec2 g = texelFetch(previousGeometry, q, 0).xy;
        float previousDepth = uintBitsToFloat(g.x);
        if (blDenoiseSky(previousDepth)) continue;
        vec3 previousWorld = blDenoiseWorld(params.inversePreviousViewProjection, vec2(q), previousDepth);
        bool samePlane = abs(dot(previousWorld - world, n)) <= tolerance;
        bool sameNormal = dot(blDenoiseUnpackNormal(g.y), n) > 0.9;
        if (samePlane && sameNormal && w > 0.0) {
            sum += w * texelFetch(previousHistory, q, 0);
            weights += w;
        }
    }
    bool reprojected = weights > 1e-3 && params.options.y == 0u;
    vec3 previous = reprojected ? sum.xyz / weights : vec3(0.0);
    float frames = reprojected ? min(previous.z + 1.0, float(params.options.x)) : 1.0;
    vec2 local = neighbourhood(pixel);
    float clamped = clamp(previous.x, local.x - params.normalScale.w * local.y, local.x + params.normalScale.w * local.y);
    float alpha = 1.0 / frames;
    float mean = mix(clamped, answer, alpha);
    float moment = mix(previous.y, answer, alpha);
    imageStore(history, pixel, vec4(mean, max(moment, mean * mean), frames, 0.0));
}
