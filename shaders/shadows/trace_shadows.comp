#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Hybrid shadows' rays (shadows::ShadowClassifier::trace): dispatched indirectly, 32 threads per listed tile and 8
// tiles per group; each pixel of the tile's ray mask traces one ray towards the sun's centre (soft shadows: a point of
// the sun's disc) through the distance field (bricklight/trace.glsl) over the tile's interval, and the tile's hit-mask
// texel takes the rays' answers in place of the shadow maps' for those pixels. The votes meet in shared memory (no
// subgroup operations).
// Soft rays and the interval: a ray θ ≤ α/2 off the centre meets a blocker depth D (along the centre) at D / cos θ ≤
// D·(1 + tan²(α/2)/2), never before D, so the start holds; the end was widened by the search radius tan(α/2)·Z (Z ≥ D,
// the receiver's distance from the map's depth 0), more than D·tan²(α/2)/2 for any α < 2 rad, and sideways the ray
// stays within that radius of the centre ray, the disc the blocker search covered.
layout(local_size_x = 256, local_size_y = 1, local_size_z = 1) in;
#include "shadow_params.glsl"
#include "bricklight/trace.glsl"  // the field at its default slots: atlas texture 15, read buffers 4..7
// Storage buffer 7 (free here): the application's GI alpha cache, or the classifier's stand-in whose header says none.
#include "bricklight/alpha_cache.glsl"
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_TEXTURE(1) uniform sampler2D normalTexture;
BL_READ_BUFFER(1) Tiles { uvec4 tiles[]; } list;
BL_READ_BUFFER(2) Counts { uint counts[8]; } count;  // [7]: the listed tiles
BL_IMAGE(0, r32ui) uniform uimage2D hitMask;
BL_IMAGE(1, r32ui) uniform uimage2D sureMask;

shared uint hits[8], decided[8];

uint hashPixel(uvec2 p) {
    uint v = (p.x | (p.y << 16u)) * 747796405u + 2891336453u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (v >> 22u) ^ v;
}

// A point of the sun's disc, uniform over the disc in the plane perpendicular to the sun (its tangent plane at
// distance 1: radius tan(α/2)): the R2 sequence over the frame index (in 32-bit fixed point, exact on every
// backend) rotated per pixel by a hash, so that neighbours draw different points and each pixel's points over
// frames cover the disc evenly.
vec3 sunSample(vec3 sun, ivec2 pixel) {
    uint h = hashPixel(uvec2(pixel));
    uint frame = uint(params.trace.w);
    uvec2 fixedPoint = uvec2(h << 16u, h & 0xFFFF0000u) + frame * uvec2(3242174889u, 2447445413u);
    vec2 u = vec2(fixedPoint >> 8u) * (1.0 / 16777216.0);
    float r = params.trace.z * sqrt(u.x), phi = 6.28318530718 * u.y;
    vec3 t = normalize(cross(sun, abs(sun.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(sun, t);
    return normalize(sun + r * (cos(phi) * t + sin(phi) * b));
}

// Foliage. A ray goes on past a hit the field flags as alpha-tested with the probability that the card is cut out
// there (1 − the alpha cache's coverage): a draw per pixel, frame and layer, so that over frames the hit mask averages
// to the partial visibility through the cards, which the shadow denoiser's history accumulates. Layer 0 (the first
// card met) draws a golden-ratio sequence over frames shifted per pixel by a hash (each pixel's frames stratify its
// draws: the average converges as 1/N, not 1/√N); deeper layers draw white noise per frame, independent of layer 0
// (two layers sharing one sequence would pass together or not: a per-pixel bias the frames never average out). The
// hash differs from the sun sample's, so that the disc point and the draws are not tied. Deterministic, integer only:
// the same on every backend.
#define SHADOW_FOLIAGE_MAX_LAYERS 6u  // cards a ray may pass; its next alpha-tested hit blocks (as the GI's rays)
#define SHADOW_FOLIAGE_MAX_TRACES 10u  // traces in all: a card's shell met again (below) costs a trace, not a draw

uint mixBits(uint v) {
    v = v * 747796405u + 2891336453u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (v >> 22u) ^ v;
}

float foliageDraw(ivec2 pixel, uint layer) {
    uint frame = uint(params.trace.w);
    uint h = mixBits(hashPixel(uvec2(pixel)) ^ 0x68E31DA4u);
    uint bits = layer == 0u ? h + frame * 2654435769u : mixBits(h ^ mixBits(frame * 8u + layer));
    return float(bits >> 8u) * (1.0 / 16777216.0);
}

// The cards the thin sure ray passed: where it crossed each (its hit + its epsilon over the cosine).
float thinPassed[SHADOW_FOLIAGE_MAX_LAYERS];
uint thinPassedCount;

// blSdfTrace that goes on past the cut-out parts of alpha-tested cards.
// A hit within the shell of the card the ray just passed is that card again, not a new one: blSdfContinueRay steps
// at most 3 brixels past a hit, and a ray with a wide epsilon (the fat sure ray: 1.2 brixels) crossing a card
// obliquely is still within its epsilon of it there; drawing again would make the card more opaque to fat rays than
// to thin ones. The shell ends where the ray is its epsilon past the card's plane: 2.5 epsilons (the field's
// interpolation slack included) over the cosine to the card, past the hit. An opaque hit there (BlSdfHit::alphaTested
// false) still blocks.
// followThin (the fat sure ray, after a thin one that missed): a card the thin ray crossed within this hit's shell is
// passed as the thin ray passed it, without a draw of its own. Its own draw could differ: the fat ray stops up to
// 1.2 brixels before the card, where the cache's cells differ (or, in the neighbouring brick, hold no counts:
// unknown, opaque); with their own draws 9 % of the test card's answers were unsure, all of them lit ones, which
// biased the sure answers towards shadow (tests/shadows/shadow_foliage_tests.cpp).
// recordPassed (the thin sure ray): note the cards passed for the fat ray.
BlSdfHit traceThroughFoliage(BlSdfRay ray, ivec2 pixel, bool followThin, bool recordPassed) {
    BlSdfHit hit = blSdfTrace(ray);
    uint layer = 0u;
    float shellEnd = -1.0;
    for (uint k = 0u; k < SHADOW_FOLIAGE_MAX_TRACES && hit.hit && hit.alphaTested; ++k) {
        if (hit.t > shellEnd) {
            float eps = blSdfTable.cascades[hit.cascade].voxelSize.z * ray.epsilonScale;
            float toCard = eps / max(abs(dot(hit.normal, ray.direction)), 0.1);
            shellEnd = hit.t + 2.5 * toCard;
            bool crossedByThin = false;
            for (uint i = 0u; followThin && i < thinPassedCount; ++i)
                crossedByThin = crossedByThin || (thinPassed[i] >= hit.t && thinPassed[i] <= shellEnd);
            if (layer == SHADOW_FOLIAGE_MAX_LAYERS) {
                blAlphaCacheCountBoundReached();  // its next card blocks, whatever the cache says
                break;
            }
            if (!crossedByThin && !blAlphaCacheTransparent(hit, foliageDraw(pixel, layer))) break;
            if (recordPassed) thinPassed[layer] = hit.t + toCard;
            ++layer;
            thinPassedCount = recordPassed ? layer : thinPassedCount;
        }
        ray = blSdfContinueRay(ray, hit);
        hit = blSdfTrace(ray);
    }
    return hit;
}

// The hit epsilon and brixel (world units) of the finest cascade that holds p: the field's resolution at the receiver.
vec2 fieldResolutionAt(vec3 p) {
    vec2 r = vec2(0.0);
    bool found = false;
    uint cascades = blSdfTable.header.x;
    for (uint c = 0u; c < cascades; ++c) {
        BlSdfCascade info = blSdfTable.cascades[c];
        vec3 local = p * info.voxelSize.y - vec3(info.origin.xyz);
        bool inside = info.origin.w != 0 && all(greaterThanEqual(local, vec3(0.0))) && all(lessThan(local, vec3(64.0)));
        if (inside && !found) {
            r = vec2(info.voxelSize.z, info.voxelSize.x / 7.0);
            found = true;
        }
        if (!found) r = vec2(info.voxelSize.z, info.voxelSize.x / 7.0);  // beyond every cascade: the coarsest
    }
    return r;
}

void main() {
    uint slot = gl_LocalInvocationID.x >> 5u, lane = gl_LocalInvocationID.x & 31u;
    uint index = gl_WorkGroupID.x * 8u + slot;
    bool listed = index < count.counts[7];
    uvec4 record = listed ? list.tiles[index] : uvec4(0u);
    ivec2 tile = ivec2(record.x & 0xFFFFu, record.x >> 16u);
    ivec2 pixel = tile * ivec2(8, 4) + ivec2(lane & 7u, lane >> 3u);
    uint bit = 1u << lane;
    if (lane == 0u) {
        hits[slot] = 0u;
        decided[slot] = 0u;
    }
    barrier();
    if ((record.y & bit) != 0u) {
        float depth = texelFetch(depthTexture, pixel, 0).r;
        vec3 n = normalize(texelFetch(normalTexture, pixel, 0).xyz * params.normalScale.xyz + params.normalBias.xyz);
        vec3 position = blShadowWorldPosition(pixel, depth);
        vec3 origin = position + n * params.trace.x;
        vec3 direction = sunSample(params.sun.xyz, pixel);
        float t0 = uintBitsToFloat(record.z), t1 = uintBitsToFloat(record.w);
        bool sure = params.trust.w != 0.0;
        bool hit = false, known = true;
        if (sure) {
            // Sure rays: a thin ray (a fraction of the hit epsilon) hits only where it passes through a surface; a fat
            // one misses only where nothing lies within the field's interpolation error of it. Each starts where its
            // own epsilon no longer sees the receiver's plane along the ray.
            // Through foliage the question "is this answer sure" stays geometric: a card is present or cut out by a
            // draw, and the draw is a sample, not an uncertainty to hand back to the maps. Both rays draw the same
            // numbers per layer (foliageDraw(pixel, layer)), so at a card they agree: thin and fat both pass it (lit,
            // if nothing else blocks: sure) or both stop (the thin ray's hit: shadowed, sure). They part only where
            // the cache's coverage differs at their two hit points (the fat ray's lies up to its epsilon before the
            // card) or the fat ray meets a surface the thin one passed beside; then the fat ray hits, the answer is
            // unsure and the maps keep it, as for an opaque edge. A fixed frameIndex (hard sun without a denoiser)
            // keeps each pixel's draws: a stable dither, no flicker.
            vec2 res = fieldResolutionAt(position);
            float cosine = dot(n, direction);
            float slope = 1.0 / max(cosine, 0.1);
            float thinStart = (params.trust.x * res.x + params.trust.z * res.y) * slope;
            float fatStart = (params.trust.y * res.x + params.trust.z * res.y) * slope;
            BlSdfRay thin = blSdfMakeRay(origin, direction, max(t0, thinStart), t1);
            thin.epsilonScale = params.trust.x;
            thinPassedCount = 0u;
            BlSdfHit h = traceThroughFoliage(thin, pixel, false, true);
            // A disc sample below the receiver's horizon: the receiver itself blocks it.
            hit = h.hit || cosine <= 0.0;
            if (!hit) {
                BlSdfRay fat = blSdfMakeRay(origin, direction, max(t0, fatStart), t1);
                fat.epsilonScale = params.trust.y;
                BlSdfHit f = traceThroughFoliage(fat, pixel, true, false);
                // A miss is sure only where the fat ray covered the whole interval the taps asked for.
                known = !f.hit && !f.gaveUp && t0 >= fatStart;
            }
        } else {
            BlSdfRay ray = blSdfMakeRay(origin, direction, t0, t1);
            ray.epsilonScale = params.trace.y;
            hit = traceThroughFoliage(ray, pixel, false, false).hit;
        }
        if (hit) atomicOr(hits[slot], bit);
        if (known) atomicOr(decided[slot], bit);
    }
    barrier();
    if (lane == 0u && listed) {
        // Only the decided bits change: the others keep the shadow maps' answer.
        uint mask = record.y & decided[slot];
        uint before = imageLoad(hitMask, tile).x;
        imageStore(hitMask, tile, uvec4((before & ~mask) | (hits[slot] & mask)));
        imageStore(sureMask, tile, uvec4(imageLoad(sureMask, tile).x | mask));
    }
}
