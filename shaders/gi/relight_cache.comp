#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_alpha.glsl"
// Pass 4b: re-light the radiance cache where the camera does not see. The screen injects only what it
// sees, so light that changes out of view (a lamp switched off behind the camera) would stay in the cache
// for ever. For each brick of this frame's relight list (clear_freed_bricks.comp picks bricks unseen for a
// few frames), one thread per written texel: the surface near the texel (the distance field's gradient
// and distance), then
//   radiance = emission + albedo · (E_lights / π + mean of GI_RELIGHT_HALVES cosine-weighted rays' radiance)
// with the lights shadowed through the field and the rays reading the cache (the environment on a miss):
// one more bounce each time, as the screen's feedback gives on screen. Albedo and emission are the brick's
// (learnt by inject_radiance.comp where the camera saw it): one value per brick, so texels of a brick
// that spans two materials get their mean.
// One group per listed brick, two threads per texel: each traces one cosine-weighted ray and half of the
// lights' shadow rays, and the two halves meet in shared memory. (One thread per texel tracing all of them
// in series was slower: the pass's time is that of its longest thread.)
layout(local_size_x = 128) in;
#define GI_RELIGHT_HALVES 2u
// How far a re-lit texel moves towards the new value (a brick is re-lit every GI_RELIGHT_PERIOD frames).
#define GI_RELIGHT_BLEND 0.75
BL_READ_BUFFER(0) RelightList { uint relightList[]; };
BL_READ_BUFFER(1) BrickOwners { uint brickOwners[]; };
BL_READ_BUFFER(2) BrickMaterial { uint brickMaterial[]; };
BL_READ_BUFFER(3) Lights { vec4 giLights[]; };  // 4 per light (core/gi/gi_constants.h: GpuLight)
BL_IMAGE(0, r32ui) uniform coherent uimage3D giRadianceCache;
BL_STORAGE_BUFFER(0) CacheSlots { uint giCacheSlots[]; };  // read only here (the read-buffer slots are taken)
#define GI_CACHE_SLOTS_DECLARED
#include "gi_environment.glsl"
#define GI_USES_RADIANCE_CACHE
#include "gi_bricks.glsl"
#include "gi_lights.glsl"

// Outward unit normal and distance (world) of the surface near brick-local uvw. The field is unsigned, so
// its gradient points away from the surface on the texel's own side — the side the camera saw, since
// injection moves half a texel towards it. A texel centre right on the surface has no useful gradient:
// the neighbouring point (an eighth of a voxel away) farthest from the surface stands in for it.
bool giSurfaceNear(uint brick, vec3 uvw, float band, out vec3 n, out float distance) {
    const float h = 1.0 / 7.0;
    vec3 at = uvw;
    float best = blSdfSampleBrick(brick, uvw);
    if (best < 0.5 * h) {
        for (int i = 0; i < 6; ++i) {
            vec3 o = uvw;
            o[i >> 1] += (i & 1) == 0 ? 0.125 : -0.125;
            float s = blSdfSampleBrick(brick, o);
            if (s > best) {
                best = s;
                at = o;
            }
        }
    }
    vec3 g = vec3(blSdfSampleBrick(brick, at + vec3(h, 0, 0)) - blSdfSampleBrick(brick, at - vec3(h, 0, 0)),
                  blSdfSampleBrick(brick, at + vec3(0, h, 0)) - blSdfSampleBrick(brick, at - vec3(0, h, 0)),
                  blSdfSampleBrick(brick, at + vec3(0, 0, h)) - blSdfSampleBrick(brick, at - vec3(0, 0, h)));
    float len = length(g);
    if (!(len > 1e-4) || best >= 0.999) return false;  // no surface within the band
    n = g / len;
    distance = blSdfSampleBrick(brick, uvw) * band;
    return true;
}

// What the second thread of each texel hands over: its ray (rgb; w 1 if it voted) and its lights.
shared vec4 halfBounce[64];
shared vec3 halfIrradiance[64];

void main() {
    uint slot = gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;
    if (slot >= min(relightList[3], GI_RELIGHT_BUDGET)) return;
    uint entry = relightList[4u + slot];
    uint brick = entry & ~GI_RELIGHT_CARD_SIDES;
    bool cardSidesOnly = (entry & GI_RELIGHT_CARD_SIDES) != 0u;
    uint owner = brickOwners[brick];
    if (owner == BL_SDF_NO_OWNER) return;
    uint cacheSlot = giCacheSlots[brick];
    if (cacheSlot >= GI_SLOT_PENDING) return;
    // Every return above is the whole group's (one brick); below, threads only go idle until the barrier.
    uint t = gl_LocalInvocationIndex % 64u, side = gl_LocalInvocationIndex / 64u;
    ivec3 local = ivec3(t & 3u, (t >> 2) & 3u, t >> 4);
    ivec3 texel = giCacheSlotBase(cacheSlot) + local;
    uint old = imageLoad(giRadianceCache, texel).r;
    uint cascade;
    ivec3 voxel = giOwnerVoxel(owner, cascade);
    BlSdfCascade info = blSdfTable.cascades[cascade];
    vec3 uvw = (vec3(local) + 0.5) / 4.0;
    vec3 n = vec3(0.0, 0.0, 1.0);
    float distance = 0.0;
    // Texels never seen have nothing to re-light; nor have texels with no surface within the band. Cards are the
    // exception (docs/gi.md, "Foliage"): a card is thinner than a texel, so its two sides have texels of their own
    // (inject_radiance.comp writes the side the camera sees, half a texel off the surface), and the camera never
    // sees the other side — leaving it unwritten made rays that meet it read the lit side from a coarser cascade,
    // or count as unknown and take the mean of the probe's other hits: foliage came out 2× too bright. In the
    // cells of a brick's cards, texels are re-lit written or not; while the brick is in view (cardSidesOnly) only
    // those on the far side of their surface from the camera. (Re-lighting unwritten texels that face the camera
    // too — parts of cards hidden behind other cards — lit them with sun that the field's coarse shadow rays let
    // through: the grass's light was 1.9× the path tracer's instead of 1.8×, relMSE 0.113 instead of 0.083.)
    bool cards = giBrickHoldsCards(brick) && blSdfCellAlphaTested(brick, uvw);
    bool relit = (cardSidesOnly ? cards : old != 0u || cards) && giSurfaceNear(brick, uvw, info.voxelSize.w, n, distance);
    vec3 q = (vec3(voxel) + uvw) * info.voxelSize.x;
    if (relit && cardSidesOnly) relit = dot(n, giFrame.camera.xyz - q) < 0.0;
    vec3 p = vec3(0.0);
    vec4 bounce = vec4(0.0);  // rgb radiance of this thread's ray, w 1 if it voted
    vec3 irradiance = vec3(0.0);
    bool emissionInRays = (giFrame.relight.y & GI_RELIGHT_EMISSION_IN_RAYS) != 0u;
    // With the emitters among the lights, neither the rays nor the texel's own value take emission.
    bool emittersInLights = (giFrame.relight.y & GI_RELIGHT_EMITTERS_IN_LIGHTS) != 0u;
    if (relit) {
        vec3 s = q - n * distance;
        p = s + n * giPushOff(s, giFrame.trace.x);
        // Cosine-weighted: the mean radiance is the irradiance over π.
        uint rng = giPcg(brick * 128u + gl_LocalInvocationIndex + giPcg(giFrameIndex()));
        vec3 tangent, bitangent;
        giBasis(n, tangent, bitangent);
        float u1 = giRandom(rng), phi = 2.0 * GI_PI * giRandom(rng);
        float sr = sqrt(u1);
        vec3 d = normalize(tangent * (sr * cos(phi)) + bitangent * (sr * sin(phi)) + n * sqrt(max(1.0 - u1, 0.0)));
        // No answer, or a surface of unknown radiance: no vote. One bounce only (GI_RELIGHT_DIRECT_ONLY): no ray,
        // unless the direct lighting holds the environment (GI_RELIGHT_ENVIRONMENT_IN_DIRECT): the environment is
        // then direct light, which the texel stands in for, and the ray asks only whether it is seen (a hit votes 0).
        bool directOnly = (giFrame.relight.y & GI_RELIGHT_DIRECT_ONLY) != 0u;
        bool environmentIsDirect = (giFrame.relight.y & GI_RELIGHT_ENVIRONMENT_IN_DIRECT) != 0u;
        BlSdfHit hit;
        hit.gaveUp = true;
        if (!directOnly || environmentIsDirect) hit = giTraceThroughAlpha(giMakeRay(p, d, giFrame.trace.w, GI_RAY_DIFFUSE), rng);
        vec3 radiance;
        if (!hit.gaveUp) {
            if (!hit.hit) bounce = vec4(giEnvironment(d), 1.0);
            else if (directOnly) bounce = vec4(0.0, 0.0, 0.0, 1.0);
            else if (giRadianceAtSide(p + d * hit.t, hit.brickId, hit.brickUvw, hit.cascade, hit.alphaTested ? hit.normal : vec3(0.0), radiance)) {
                uint e = brickMaterial[hit.brickId * GI_MATERIAL_WORDS + 1u];
                bounce = vec4(radiance + (emissionInRays && e != 0u ? blDecodeRgb9e5(e) : vec3(0.0)), 1.0);
            }
        }
        irradiance = giLightIrradiance(p, n, side, GI_RELIGHT_HALVES);
    }
    if (side == 1u) {
        halfBounce[t] = bounce;
        halfIrradiance[t] = irradiance;
    }
    barrier();
    if (side == 1u || !relit) return;
    bounce += halfBounce[t];
    irradiance += halfIrradiance[t];
    uint m = brick * GI_MATERIAL_WORDS;
    vec3 albedo = unpackUnorm4x8(brickMaterial[m]).rgb;
    // The texel's own emission, where the cache (like the lit image) holds it; else the rays see it.
    vec3 emitted = brickMaterial[m + 1u] != 0u && !emissionInRays && !emittersInLights ? blDecodeRgb9e5(brickMaterial[m + 1u]) : vec3(0.0);
    vec3 target = emitted + albedo * (irradiance / GI_PI + (bounce.w > 0.0 ? bounce.rgb / bounce.w : vec3(0.0)));
    if (!giFinite(target)) return;
    imageStore(giRadianceCache, texel, uvec4(blEncodeRgb9e5(old == 0u ? target : mix(blDecodeRgb9e5(old), target, GI_RELIGHT_BLEND))));
}
