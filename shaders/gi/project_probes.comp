#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_sh.glsl"
// Pass 12: each probe's 64 radiance texels into L2 SH. One group per probe; every thread projects its
// texel (the texel's centre direction, solid angle 2π/64), then a parallel reduction in shared memory sums
// the 64 projections. Hits of unknown radiance take the mean of the probe's known hits (a first reduction);
// empty texels are left out and the rest scaled up to cover the hemisphere.
// Output per probe: 9 vec4 (rgb coefficient; w of the first = the fraction of texels with data).
layout(local_size_x = 64) in;
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_TEXTURE(0) uniform sampler2D probes;
BL_STORAGE_BUFFER(0) ProbeSH { vec4 probeSH[]; };
BL_IMAGE(0, r32ui) uniform readonly uimage3D giRadianceCache;
#define GI_USES_RADIANCE_CACHE
#include "gi_bricks.glsl"

// The radiance leaving the probe's own surface (the radiance cache there, finest cascade with data).
bool giSurfaceRadiance(vec3 p, vec3 n, out vec3 radiance) {
    for (uint c = giFrame.cascades.x; c <= giFrame.cascades.y; ++c) {
        uint brick;
        vec3 uvw;
        if (!giBrickAt(p + n * (0.125 * giVoxelSize(c)), c, brick, uvw) && !giBrickAt(p, c, brick, uvw)) continue;
        float w;
        radiance = giSampleRadianceCache(brick, uvw, w);
        if (w > 0.0) return true;
    }
    return false;
}

// [value][thread]: a thread's neighbours in a reduction step are neighbours in memory (no bank conflicts;
// [thread][value] had a stride of 28 words, four threads per bank).
shared float partial[28][64];
shared vec4 ownRadiance;  // the probe's own surface (giSurfaceRadiance); w 1 where a cache knows it

void main() {
    uvec2 tile = gl_WorkGroupID.xy;
    uint index = tile.y * giFrame.tiles.x + tile.x;
    uint t = gl_LocalInvocationIndex;
    uvec4 info = probeInfo[index];
    uvec2 local = uvec2(t % 8u, t / 8u);
    vec4 radiance = texelFetch(probes, ivec2(tile * 8u + local), 0);
    vec3 n = giProbeNormal(info);
    if (t == 0u) {  // first: the chain of lookups overlaps the reductions instead of following them
        vec3 own = vec3(0.0);
        bool known = (info.w & GI_PROBE_VALID) != 0u &&
                     giSurfaceRadiance(giWorldPosition(giPixelUv(giProbePixel(info)), uintBitsToFloat(info.y), giCamera.inverseViewProjection), n, own);
        ownRadiance = vec4(own, known ? 1.0 : 0.0);
    }
    bool probeValid = (info.w & GI_PROBE_VALID) != 0u && giFinite(radiance.rgb);
    // First reduction: the mean of the known hits, which stands in for the hits of unknown radiance.
    bool knownHit = probeValid && radiance.a > GI_TEXEL_MISS + 0.1;
    partial[0][t] = knownHit ? radiance.r : 0.0;
    partial[1][t] = knownHit ? radiance.g : 0.0;
    partial[2][t] = knownHit ? radiance.b : 0.0;
    partial[3][t] = knownHit ? 1.0 : 0.0;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1) {
        if (t < stride)
            for (int k = 0; k < 4; ++k) partial[k][t] += partial[k][t + stride];
        barrier();
    }
    vec4 hits = vec4(partial[0][0], partial[1][0], partial[2][0], partial[3][0]);
    barrier();
    bool unknownHit = probeValid && abs(radiance.a - GI_TEXEL_UNKNOWN_HIT) < 0.1;
    if (unknownHit && hits.w > 0.0) radiance = vec4(hits.rgb / hits.w, GI_TEXEL_HIT);
    bool use = probeValid && radiance.a > GI_TEXEL_UNKNOWN_HIT + 0.1;
    float y[9];
    giShBasis(giProbeDirection(n, (vec2(local) + 0.5) / 8.0), y);
    for (int i = 0; i < 9; ++i) {
        vec3 c = use ? radiance.rgb * (y[i] * 2.0 * GI_PI / 64.0) : vec3(0.0);
        partial[3 * i][t] = c.r;
        partial[3 * i + 1][t] = c.g;
        partial[3 * i + 2][t] = c.b;
    }
    partial[27][t] = use ? 1.0 : 0.0;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1) {
        if (t < stride)
            for (int k = 0; k < 28; ++k) partial[k][t] += partial[k][t + stride];
        barrier();
    }
    if (t < 9u) {
        // The lower hemisphere is what a point just off the surface sees below it: the surface itself.
        // Filling it with the surface's own radiance (not zero) makes the SH a whole-sphere estimate, so a
        // pixel or a world-cache brick with another normal reads it correctly; for the probe's own normal
        // it changes nothing (the L2 clamped-cosine kernel integrates to 0 over the lower hemisphere).
        // Its projection is the SH of a constant over the lower hemisphere: c·(√π, 0, -√(3π)/2, 0, ...)
        // rotated to n, i.e. c·Y-weights evaluated analytically below.
        vec3 self = ownRadiance.w > 0.0 ? ownRadiance.rgb : (hits.w > 0.0 ? hits.rgb / hits.w : vec3(0.0));
        float covered = partial[27][0];
        float scale = covered > 0.0 ? 64.0 / covered : 0.0;
        vec3 c = vec3(partial[3 * t][0], partial[3 * t + 1][0], partial[3 * t + 2][0]) * scale;
        if (covered > 0.0) {
            // ∫ over the lower hemisphere of Y_lm: zonal coefficients (l0: 2π·0.282095, l1: -π·0.488603,
            // l2: 0) along n.
            float yn[9];
            giShBasis(n, yn);
            float zonal = t == 0u ? 2.0 * GI_PI * 0.282095 : (t < 4u ? -GI_PI * 0.488603 * yn[t] / 0.488603 : 0.0);
            c += self * zonal;
        }
        probeSH[index * 9u + t] = vec4(c, t == 0u ? covered / 64.0 : 0.0);
    }
}
