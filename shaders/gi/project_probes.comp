#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
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

shared float partial[64][28];

void main() {
    uvec2 tile = gl_WorkGroupID.xy;
    uint index = tile.y * giFrame.tiles.x + tile.x;
    uint t = gl_LocalInvocationIndex;
    uvec4 info = probeInfo[index];
    uvec2 local = uvec2(t % 8u, t / 8u);
    vec4 radiance = texelFetch(probes, ivec2(tile * 8u + local), 0);
    bool probeValid = (info.w & GI_PROBE_VALID) != 0u && giFinite(radiance.rgb);
    // First reduction: the mean of the known hits, which stands in for the hits of unknown radiance.
    bool knownHit = probeValid && radiance.a > GI_TEXEL_MISS + 0.1;
    partial[t][0] = knownHit ? radiance.r : 0.0;
    partial[t][1] = knownHit ? radiance.g : 0.0;
    partial[t][2] = knownHit ? radiance.b : 0.0;
    partial[t][3] = knownHit ? 1.0 : 0.0;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1) {
        if (t < stride)
            for (int k = 0; k < 4; ++k) partial[t][k] += partial[t + stride][k];
        barrier();
    }
    vec4 hits = vec4(partial[0][0], partial[0][1], partial[0][2], partial[0][3]);
    barrier();
    bool unknownHit = probeValid && abs(radiance.a - GI_TEXEL_UNKNOWN_HIT) < 0.1;
    if (unknownHit && hits.w > 0.0) radiance = vec4(hits.rgb / hits.w, GI_TEXEL_HIT);
    bool use = probeValid && radiance.a > GI_TEXEL_UNKNOWN_HIT + 0.1;
    float y[9];
    giShBasis(giProbeDirection(giProbeNormal(info), (vec2(local) + 0.5) / 8.0), y);
    for (int i = 0; i < 9; ++i) {
        vec3 c = use ? radiance.rgb * (y[i] * 2.0 * GI_PI / 64.0) : vec3(0.0);
        partial[t][3 * i] = c.r;
        partial[t][3 * i + 1] = c.g;
        partial[t][3 * i + 2] = c.b;
    }
    partial[t][27] = use ? 1.0 : 0.0;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1) {
        if (t < stride)
            for (int k = 0; k < 28; ++k) partial[t][k] += partial[t + stride][k];
        barrier();
    }
    if (t < 9u) {
        float covered = partial[0][27];
        float scale = covered > 0.0 ? 64.0 / covered : 0.0;
        vec3 c = vec3(partial[0][3 * t], partial[0][3 * t + 1], partial[0][3 * t + 2]) * scale;
        probeSH[index * 9u + t] = vec4(c, t == 0u ? covered / 64.0 : 0.0);
    }
}
