#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The reflection classifier (reflections::ReflectionClassifier::classify): one 64-thread group per 8×8 tile.
// Thread 0 picks the tile's class from the hit counters of the last frame, carried along the motion at a random
// pixel of the tile and max-pooled over the 3×3 tiles around (the safe band), by a dice roll against
// spawnRate + hits − missWeight·misses for this frame's bytes and the last frame's; the two disagreeing makes the
// tile a checkerboard. Each pixel then asks for a ray (glossy, and a base ray of samplesPerQuad) and the rays are
// compacted through shared memory (never subgroup operations: lavapipe's subgroups are 8 wide) into the
// screen-space list, padded to a multiple of 32 per tile with helper entries so that every 32-wide group of the
// trace works on one tile, and the SDF list.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "reflection_params.glsl"
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_TEXTURE(1) uniform sampler2D normalTexture;
BL_TEXTURE(2) uniform sampler2D roughnessTexture;
BL_TEXTURE(3) uniform sampler2D motionTexture;  // a 1×1 stand-in without motion vectors (read, not used)
BL_STORAGE_BUFFER(0) ScreenList { uint screenRays[]; } screenList;
BL_STORAGE_BUFFER(1) SdfList { uint sdfRays[]; } sdfList;
BL_STORAGE_BUFFER(2) DenoiseList { uint denoiseTiles[]; } denoiseList;
// Words (ReflectionClassifier's header): 0..8 dispatch arguments (reflection_args.comp), 9 screen entries,
// 11 SDF rays, 12 denoiser tiles: the only global atomics, three per tile. The statistics go per tile to tileInfo
// and tileStats and are summed on the CPU (readCounts): same-address atomics from every group bound the pass.
BL_STORAGE_BUFFER(3) Counts { uint counts[24]; } count;
BL_IMAGE(0, r32ui) uniform readonly uimage2D history;
BL_IMAGE(1, r32ui) uniform writeonly uimage2D counter;
BL_IMAGE(2, r32ui) uniform writeonly uimage2D tileInfo;
BL_IMAGE(3, r32ui) uniform writeonly uimage2D tileStats;  // surface, glossy, SDF rays, ray pixels: a byte each

shared uint glossyBits[2];  // bit (y·8 + x) of the tile: glossy
shared uint tileClass, screenCount, sdfCount, screenBase, sdfBase, surfaceCount, glossyCount;

// The dice of a tile in a frame (a different stream from the random pixel's).
float dice(uvec2 tile, uint frame) { return blReflectionUnit(blReflectionHash3(uvec3(tile, frame ^ 0x9E3779B9u))); }

bool screenSpaceFirst(uint hits, uint misses, float rnd) {
    return rnd <= params.hybrid.y + float(hits) - params.hybrid.x * float(misses);
}

void main() {
    uvec2 tile = gl_WorkGroupID.xy;
    uvec2 local = gl_LocalInvocationID.xy;
    uint lane = local.y * 8u + local.x;
    ivec2 pixel = ivec2(tile * 8u + local);
    ivec2 size = ivec2(params.size.xy);
    ivec2 tiles = ivec2(params.size.zw);
    uint frame = params.frame.x;

    if (lane == 0u) {
        glossyBits[0] = 0u;
        glossyBits[1] = 0u;
        screenCount = 0u;
        sdfCount = 0u;
        surfaceCount = 0u;
        glossyCount = 0u;
        // Where the tile was: the motion at one random pixel of it.
        uint r = blReflectionHash3(uvec3(tile, frame));
        ivec2 probe = min(ivec2(tile * 8u + uvec2(r & 7u, (r >> 3u) & 7u)), size - 1);
        float probeDepth = texelFetch(depthTexture, probe, 0).r;
        vec2 centre = vec2(probe) + 0.5, uv = centre / vec2(size);
        bool hasMotion = params.options2.w != 0u;
        vec2 given = texelFetch(motionTexture, probe * int(params.options2.w), 0).xy * params.hybrid.zw;
        vec4 previousClip = params.previousViewProjection * vec4(blReflectionWorldPosition(centre, probeDepth), 1.0);
        bool cameraMotion = !blReflectionIsSky(probeDepth) && previousClip.w > 0.0;
        // The sky has no depth to carry: it keeps its place.
        vec2 fromCamera = cameraMotion ? uv - (previousClip.xy / previousClip.w * 0.5 + 0.5) : vec2(0.0);
        vec2 motion = hasMotion ? given : fromCamera;
        ivec2 from = ivec2(floor((uv - motion) * vec2(size) / 8.0));
        bool inside = all(greaterThanEqual(from, ivec2(0))) && all(lessThan(from, tiles));
        uint best = inside ? imageLoad(history, from).x : 0u;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                ivec2 t = from + ivec2(dx, dy);
                if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, tiles))) continue;
                uint c = imageLoad(history, t).x;
                if ((c & 0xFFu) > (best & 0xFFu)) best = c;
            }
        uint newHits = best & 0xFFu, newMisses = (best >> 8u) & 0xFFu;
        uint oldHits = (best >> 16u) & 0xFFu, oldMisses = best >> 24u;
        bool newScreen = screenSpaceFirst(newHits, newMisses, dice(tile, frame));
        bool oldScreen = screenSpaceFirst(oldHits, oldMisses, dice(tile, frame - 1u));
        uint byCounter = newScreen == oldScreen ? (newScreen ? 0u : 2u) : 1u;
        uint screenFirst = 0u, sdfOnly = 2u;
        uint c = params.options2.x != 0u ? byCounter : screenFirst;
        c = params.options2.z != 0u ? c : screenFirst;
        c = params.options2.y != 0u ? c : sdfOnly;
        tileClass = c;
        // This frame's counter: the last frame's new bytes become the previous ones; the trace adds the new.
        imageStore(counter, ivec2(tile), uvec4((newHits << 16u) | (newMisses << 24u)));
    }
    barrier();

    bool onScreen = all(lessThan(pixel, size));
    ivec2 p = min(pixel, size - 1);
    float depth = texelFetch(depthTexture, p, 0).r;
    bool surface = onScreen && !blReflectionIsSky(depth);
    float roughness = blReflectionRoughness(texelFetch(roughnessTexture, p, 0));
    bool glossy = surface && roughness < params.normalScale.w;
    uint perQuad = params.options.x;
    bool baseRay = perQuad == 4u || (perQuad == 2u ? ((pixel.x + pixel.y) & 1) == 0 : ((pixel.x | pixel.y) & 1) == 0);
    bool needsRay = glossy && baseRay;
    if (glossy) {
        atomicOr(glossyBits[lane >> 5u], 1u << (lane & 31u));
        atomicAdd(glossyCount, 1u);
    }
    if (surface) atomicAdd(surfaceCount, 1u);
    barrier();

    // Quad neighbours that are glossy without a ray of their own take this ray's result: with 2 per quad the
    // neighbour across x (the one across y is the other base ray's), with 1 all three.
    uint across = lane ^ 1u, below = lane ^ 8u, diagonal = lane ^ 9u;
    bool copyX = perQuad != 4u && (glossyBits[across >> 5u] & (1u << (across & 31u))) != 0u;
    bool copyY = perQuad == 1u && (glossyBits[below >> 5u] & (1u << (below & 31u))) != 0u;
    bool copyXY = perQuad == 1u && (glossyBits[diagonal >> 5u] & (1u << (diagonal & 31u))) != 0u;
    uint copyFlags = (copyX ? 1u : 0u) | (copyY ? 2u : 0u) | (copyXY ? 4u : 0u);

    uint cls = tileClass;
    uint checker = perQuad == 4u ? uint(pixel.x ^ pixel.y) & 1u : uint((pixel.x >> 1) ^ (pixel.y >> 1)) & 1u;
    bool wantsScreen = cls == 0u || (cls == 1u && checker == 0u);
    bool screenAllowed = params.options2.y != 0u;
    bool sdfAllowed = params.options2.z != 0u && roughness < params.normalBias.w;
    bool toSdf = needsRay && sdfAllowed && (!wantsScreen || !screenAllowed);
    bool toScreen = needsRay && screenAllowed && !toSdf;
    uint screenIndex = 0u, sdfIndex = 0u;
    if (toScreen) screenIndex = atomicAdd(screenCount, 1u);
    if (toSdf) sdfIndex = atomicAdd(sdfCount, 1u);
    barrier();

    uint rays = screenCount, padded = (rays + 31u) & ~31u;
    if (lane == 0u) {
        screenBase = padded > 0u ? atomicAdd(count.counts[9], padded) : 0u;
        sdfBase = sdfCount > 0u ? atomicAdd(count.counts[11], sdfCount) : 0u;
        if (rays + sdfCount > 0u) {
            uint at = atomicAdd(count.counts[12], 1u);
            denoiseList.denoiseTiles[at] = ((tile.y * 8u) << 16u) | (tile.x * 8u);
        }
        imageStore(tileInfo, ivec2(tile), uvec4(cls | (rays << 8u) | (sdfCount << 16u)));
        imageStore(tileStats, ivec2(tile), uvec4(surfaceCount | (glossyCount << 8u) | (sdfCount << 16u) | ((rays + sdfCount) << 24u)));
    }
    barrier();
    uint record = blReflectionPack(uvec2(pixel), copyFlags);
    if (toScreen) screenList.screenRays[screenBase + screenIndex] = record;
    if (toSdf) sdfList.sdfRays[sdfBase + sdfIndex] = record;
    if (lane < padded - rays) screenList.screenRays[screenBase + rays + lane] = kReflectionHelper;
}
