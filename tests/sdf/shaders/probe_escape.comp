#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
// The GI's own probe-ray code, included rather than copied, so that these rays are the screen probes' rays by
// construction (fill_probes_body.glsl: push-off, hemisphere mapping, ray parameters, the walk through the alpha
// cache): gi_common.glsl (GiFrame at constants 1, giMakeRay, giProbeDirection, giPcg), gi_bricks.glsl
// (giPushOff), gi_alpha.glsl (giTraceThroughAlpha; bricklight/alpha_cache.glsl at storage buffer 7).
#include "gi/gi_common.glsl"
#include "gi/gi_bricks.glsl"
#include "gi/gi_alpha.glsl"
// Where probe rays spawned on surfaces end (tests/gi/foliage_probe_tests.cpp): for each origin (a surface point
// and its normal, as a screen probe has them), `raysPerOrigin` rays over the hemisphere, one per cell of a
// side × side square mapped by the probes' equal-area mapping, jittered within the cell as fill_probes jitters a
// probe texel; one thread per ray. Each ray's outcome is written as a code (PROBE_*), plus PROBE_TRAPPED when it
// ends on an alpha-tested surface within one finest traced voxel of the surface point it left (PROBE_NEAR: an
// opaque one), plus the cascade of
// its last hit << 8 (a coarsened diffuse ray meets grass and ground merged in one coarse cell). The caller fills
// GiFrame's trace fields as gi::GiContext does (push-off, tMin, tMax, cascades, epsilon, iterations, coarsening)
// and binds the alpha cache — or a 16-byte stand-in of zeros, whose header says "no cache": every hit is then
// opaque, the rays of foliage built as solid.
layout(local_size_x = 64) in;
BL_CONSTANTS(2) uniform Params {
    uvec4 counts;  // x origins, y rays per origin (side², side ≤ 16), z seed (as the GI's frame index)
} params;
BL_READ_BUFFER(0) Origins { vec4 origins[]; };  // 2 per origin: position.xyz; normal.xyz (unit)
BL_STORAGE_BUFFER(0) Outcomes { uint outcomes[]; };

#define PROBE_ESCAPED 0u  // no hit before tMax: the sky
#define PROBE_OPAQUE 1u   // an opaque surface (or an alpha-tested one with no cut-out known: not flagged)
#define PROBE_CARD 2u     // a surface the field flags alpha-tested: the ray stopped inside the foliage
#define PROBE_UNKNOWN 3u  // gave up (out of iterations, or an unbuilt voxel): the GI's "unknown"
#define PROBE_TRAPPED 16u
#define PROBE_NEAR 32u  // an opaque end within one finest traced voxel of the surface point

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint rays = params.counts.y;
    if (i >= params.counts.x * rays) return;
    uint origin = i / rays, k = i % rays;
    uint side = uint(round(sqrt(float(rays))));
    uvec2 local = uvec2(k % side, k / side);
    vec3 p = origins[2u * origin].xyz, n = origins[2u * origin + 1u].xyz;
    // As giFillTexel: the texel's jitter and the walk's random numbers come from one hashed state.
    uint rng = giPcg(giPcg(origin) ^ (params.counts.z * 64u + k));
    vec2 u = (vec2(local) + vec2(giRandom(rng), giRandom(rng))) / float(side);
    vec3 d = giProbeDirection(n, u);
    BlSdfRay ray = giMakeRay(p + n * giPushOff(p, giFrame.trace.x), d, giFrame.trace.w, GI_RAY_DIFFUSE);
    BlSdfHit hit = giTraceThroughAlpha(ray, rng);
    uint outcome;
    if (hit.gaveUp) outcome = PROBE_UNKNOWN;
    else if (!hit.hit) outcome = PROBE_ESCAPED;
    else if (hit.alphaTested) {
        outcome = PROBE_CARD;
        // giFrame.camera.w: the finest traced cascade's voxel size.
        if (distance(ray.origin + d * hit.t, p) < giFrame.camera.w) outcome |= PROBE_TRAPPED;
    } else {
        outcome = PROBE_OPAQUE;
        // Near: where the ground's cells hold the grass's roots, the field cannot tell blade from ground.
        if (distance(ray.origin + d * hit.t, p) < giFrame.camera.w) outcome |= PROBE_NEAR;
    }
    if (hit.hit) outcome |= hit.cascade << 8;
    outcomes[i] = outcome;
}
