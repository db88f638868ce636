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
// (learnt by inject_radiance.comp where the camera saw it, else the field's: sdf::InstanceDesc::material): one
// value per brick, so texels of a brick that spans two materials get their mean.
// Bricks no view has lit (GI_RELIGHT_UNSEEN: a probe ray found no light at them; docs/gi.md, "Surfaces the camera
// never saw") take a cache slot here, and their texels facing a side rays wanted them from (leaning the same way
// along some axis: outside a closed room no ray wants them) whose centre lies between GI_UNSEEN_TEXEL_NEAREST and
// GI_UNSEEN_TEXEL_REACH off a surface are lit, on whichever side of it they lie (the field is unsigned: each
// texel's side has its own normal), blended more slowly (GI_UNSEEN_BLEND: their two rays are all they get). A
// texel nearer the surface has no side: lit as either, it would hand one side's light to the other. Texels the
// camera sees now are left to injection (giTexelOnScreen).
// One group per listed brick, two threads per texel: each traces one cosine-weighted ray and half of the
// lights' shadow rays, and the two halves meet in shared memory. (One thread per texel tracing all of them
// in series was slower: the pass's time is that of its longest thread.)
layout(local_size_x = 128) in;
#define GI_RELIGHT_HALVES 2u
// How far a re-lit texel moves towards the new value (a brick is re-lit every GI_RELIGHT_PERIOD frames).
#define GI_RELIGHT_BLEND 0.75
#define GI_UNSEEN_BLEND 0.25
// Texels of a brick no view has lit that are lit: those whose centre is within this many texels of a surface
// (the texels a hit's trilinear read weighs lie within one texel of the surface).
#define GI_UNSEEN_TEXEL_REACH 1.25
// In brixel intervals: beyond the 0.2-texel slack of the readers' side test (giSampleRadianceCacheSide).
#define GI_UNSEEN_TEXEL_NEAREST 0.5
BL_READ_BUFFER(0) RelightList { uint relightList[]; };
BL_READ_BUFFER(1) BrickOwners { uint brickOwners[]; };
BL_STORAGE_BUFFER(2) BrickMaterial { uint brickMaterial[]; };  // read; relight rays mark unknown hits wanted
#define giBrickMaterial brickMaterial
BL_READ_BUFFER(3) Lights { vec4 giLights[]; };  // 3 per light (core/gi/gi_constants.h: GpuLight)
BL_IMAGE(0, r32ui) uniform coherent uimage3D giRadianceCache;
coherent BL_STORAGE_BUFFER(0) CacheSlots { uint giCacheSlots[]; };  // slots for bricks no view has lit
BL_STORAGE_BUFFER(1) FreeSlots { int freeSlotCount; uint freeSlots[]; };  // a stack: popped here and by injection
BL_TEXTURE(0) uniform sampler2D internalDepth;  // this frame's (downsample.comp)
#define GI_CACHE_SLOTS_DECLARED
#include "gi_environment.glsl"
#define GI_USES_RADIANCE_CACHE
#define GI_WANTS_BRICKS
#include "gi_bricks.glsl"

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

bool giShadowed(vec3 p, vec3 l, float distance) {
    uint rng = giPcg(floatBitsToUint(p.x) ^ giPcg(floatBitsToUint(p.y) ^ giPcg(floatBitsToUint(p.z) ^ giFrameIndex())));
    BlSdfHit hit = giTraceThroughAlpha(giMakeRay(p, l, min(distance, giFrame.trace.w), GI_RAY_SHADOW), rng);
    return hit.hit || hit.gaveUp;  // no answer: in shadow, the safer guess (no light from nowhere)
}

// Albedo (rgb) and emission of a brick: learnt from the screen where the camera saw it, else the field's (zero if
// neither knows it).
vec3 giBrickAlbedo(uint brick) {
    uint learnt = brickMaterial[brick * GI_MATERIAL_WORDS];
    if ((learnt >> 24) != 0u) return unpackUnorm4x8(learnt).rgb;
    uint field = blSdfBrickMaterial(brick).x;
    return (field >> 24) != 0u ? unpackUnorm4x8(field).rgb : vec3(0.0);
}
vec3 giBrickEmission(uint brick) {
    uint m = brick * GI_MATERIAL_WORDS;
    bool learnt = (giFrame.relight.y & GI_RELIGHT_EMISSION) != 0u && (brickMaterial[m] >> 24) != 0u;
    uint e = learnt ? brickMaterial[m + 1u] : blSdfBrickMaterial(brick).y;
    return e != 0u ? blDecodeRgb9e5(e) : vec3(0.0);
}

// A cache slot for a brick no view has lit, popped from the free stack while more than giFrame.cache.y slots are
// left for the screen (GI_SLOT_NONE if none). Injection pops too: the compare-and-swap makes one of them the
// allocator, as in inject_radiance.comp.
uint giTakeSlot(uint brick) {
    if (freeSlotCount <= int(giFrame.cache.y)) return GI_SLOT_NONE;
    if (atomicCompSwap(giCacheSlots[brick], GI_SLOT_NONE, GI_SLOT_PENDING) != GI_SLOT_NONE) return GI_SLOT_NONE;
    int top = atomicAdd(freeSlotCount, -1);
    if (top <= int(giFrame.cache.y)) {
        atomicAdd(freeSlotCount, 1);
        atomicExchange(giCacheSlots[brick], GI_SLOT_NONE);
        return GI_SLOT_NONE;
    }
    uint slot = freeSlots[top - 1];
    atomicExchange(giCacheSlots[brick], slot);
    return slot;
}

// Whether the camera sees the surface a texel of a brick no view has lit stands for (its centre q, the surface's
// normal n facing q): the surface faces the camera, q projects into the view, and the depth buffer there holds a
// surface within a texel's reach (`reach`) of q's distance. Such a texel is the screen's: injection will write
// it, and a value lit here beside the injected ones would stay unrefreshed while the brick is in view.
bool giTexelOnScreen(vec3 q, vec3 n, float reach) {
    vec3 toCamera = giFrame.camera.xyz - q;
    if (dot(n, toCamera) <= 0.0) return false;
    vec4 c = giCamera.viewProjection * vec4(q, 1.0);
    if (c.w <= 0.0) return false;
    vec2 uv = c.xy / c.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return false;
    float depth = texelFetch(internalDepth, ivec2(uv * vec2(giFrame.size.xy)), 0).r;
    if (giIsSky(depth)) return false;
    float visible = length(giWorldPosition(uv, depth, giCamera.inverseViewProjection) - giFrame.camera.xyz);
    return visible > length(toCamera) - reach;
}

// Irradiance from the frame's lights first, first + stride, ... at p (normal n), shadowed through the field.
vec3 giLightIrradiance(vec3 p, vec3 n, uint first, uint stride) {
    vec3 sum = vec3(0.0);
    for (uint i = first; i < giFrame.relight.x; i += stride) {
        vec4 a = giLights[3u * i], b = giLights[3u * i + 1u], c = giLights[3u * i + 2u];
        vec3 l = b.xyz, irradiance = c.rgb;
        float distance = 1e30;
        if (a.w > 0.5) {  // point or spot
            vec3 toLight = a.xyz - p;
            float d2 = max(dot(toLight, toLight), 1e-8);
            distance = sqrt(d2);
            l = toLight / distance;
            irradiance /= d2;
            if (a.w > 1.5) {  // spot: c.w = cos(outer) < b.w = cos(inner)
                float axis = dot(-l, b.xyz);
                irradiance *= b.w > c.w ? smoothstep(c.w, b.w, axis) : step(c.w, axis);
            }
        }
        float cosine = dot(n, l);
        if (cosine <= 0.0 || all(equal(irradiance, vec3(0.0)))) continue;
        if (!giShadowed(p, l, distance)) sum += irradiance * cosine;
    }
    return sum;
}

// What the second thread of each texel hands over: its ray (rgb; w 1 if it voted) and its lights.
shared vec4 halfBounce[64];
shared vec3 halfIrradiance[64];
shared uint groupSlot;

void main() {
    uint slot = gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;
    if (slot >= min(relightList[3], GI_RELIGHT_BUDGET)) return;
    uint entry = relightList[4u + slot];
    uint brick = entry & ((1u << GI_RELIGHT_SIDES_SHIFT) - 1u);
    bool cardSidesOnly = (entry & GI_RELIGHT_CARD_SIDES) != 0u;
    bool unseen = (entry & GI_RELIGHT_UNSEEN) != 0u;
    uint wantedSides = (entry >> GI_RELIGHT_SIDES_SHIFT) & GI_SIDE_BITS;
    uint owner = brickOwners[brick];
    if (owner == BL_SDF_NO_OWNER) return;
    if (gl_LocalInvocationIndex == 0u) {
        uint s = giCacheSlots[brick];
        groupSlot = unseen && s == GI_SLOT_NONE ? giTakeSlot(brick) : s;
    }
    barrier();
    uint cacheSlot = groupSlot;
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
    bool relit = (cardSidesOnly ? cards : old != 0u || cards || unseen) && giSurfaceNear(brick, uvw, info.voxelSize.w, n, distance);
    if (relit && unseen && old == 0u)
        relit = (giSideBits(n) & wantedSides) != 0u && distance >= GI_UNSEEN_TEXEL_NEAREST * info.voxelSize.x / 7.0 &&
                distance <= GI_UNSEEN_TEXEL_REACH * 0.25 * info.voxelSize.x;
    if (relit && unseen) relit = !giTexelOnScreen((vec3(voxel) + uvw) * info.voxelSize.x, n, 0.5 * info.voxelSize.x);
    vec3 q = (vec3(voxel) + uvw) * info.voxelSize.x;
    if (relit && cardSidesOnly) relit = dot(n, giFrame.camera.xyz - q) < 0.0;
    vec3 p = vec3(0.0);
    vec4 bounce = vec4(0.0);  // rgb radiance of this thread's ray, w 1 if it voted
    vec3 irradiance = vec3(0.0);
    bool emissionInRays = (giFrame.relight.y & GI_RELIGHT_EMISSION_IN_RAYS) != 0u;
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
        BlSdfHit hit = giTraceThroughAlpha(giMakeRay(p, d, giFrame.trace.w, GI_RAY_DIFFUSE), rng);
        vec3 radiance;
        // No answer, or a surface of unknown radiance: no vote.
        if (!hit.gaveUp) {
            if (!hit.hit) bounce = vec4(giEnvironment(d), 1.0);
            else if ((giFrame.relight.y & GI_RELIGHT_DIRECT_ONLY) != 0u) bounce = vec4(giBrickEmission(hit.brickId), 1.0);
            else if (giRadianceAtSide(p + d * hit.t, hit.brickId, hit.brickUvw, hit.cascade, hit.normal, radiance)) {
                bounce = vec4(radiance + (emissionInRays ? giBrickEmission(hit.brickId) : vec3(0.0)), 1.0);
            } else {
                giWantBrick(hit.brickId, d);  // lit in turn, so that light reaches off-screen surfaces in hops
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
    vec3 albedo = giBrickAlbedo(brick);
    // The texel's own emission, where the cache (like the lit image) holds it; else the rays see it.
    vec3 emitted = emissionInRays ? vec3(0.0) : giBrickEmission(brick);
    // Without a vote the light from the other surfaces is unknown, not black: the texel keeps what it has.
    if (bounce.w == 0.0) return;
    vec3 target = emitted + albedo * (irradiance / GI_PI + bounce.rgb / bounce.w);
    if (!giFinite(target)) return;
    float blend = unseen ? GI_UNSEEN_BLEND : GI_RELIGHT_BLEND;
    imageStore(giRadianceCache, texel, uvec4(blEncodeRgb9e5(old == 0u ? target : mix(blDecodeRgb9e5(old), target, blend))));
}
