#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The reflection classifier (reflections::ReflectionClassifier::classify): 8×8 tiles, each thread one 2×2 quad,
// sixteen tiles (4 × 4, 32 × 32 pixels) per 256-thread group — a 64-thread group per tile left the GPU launching
// groups and waiting on one read at a time rather than working. The first thread of each tile picks the tile's
// class from the hit counters of the last frame, carried along the motion at a random pixel of the tile and
// max-pooled over the 3×3 tiles around (the safe band), by a dice roll against spawnRate + hits − missWeight·misses
// for this frame's bytes and the last frame's; the two disagreeing makes the tile a checkerboard. It does so while
// the other threads read their quads. Each pixel then asks for a ray (glossy, and a base ray of samplesPerQuad;
// quad neighbours without one take its result) and the rays are compacted in quad order through shared memory
// (never subgroup operations: lavapipe's subgroups are 8 wide; no atomics: each quad stores its counts, and each
// sums those before it) into the screen-space list, padded to a multiple of 32 per tile with helper entries so
// that every 32-wide group of the trace works on one tile, and the SDF list.
layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;

#include "reflection_params.glsl"
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_TEXTURE(1) uniform sampler2D normalTexture;
BL_TEXTURE(2) uniform sampler2D roughnessTexture;
BL_TEXTURE(3) uniform sampler2D motionTexture;  // a 1×1 stand-in without motion vectors (read, not used)
BL_STORAGE_BUFFER(0) ScreenList { uint screenRays[]; } screenList;
BL_STORAGE_BUFFER(1) SdfList { uint sdfRays[]; } sdfList;
BL_STORAGE_BUFFER(2) DenoiseList { uint denoiseTiles[]; } denoiseList;
// Words (ReflectionClassifier's header): 0..8 dispatch arguments (reflection_args.comp), 9 screen entries,
// 11 SDF rays, 12 denoiser tiles: the only global atomics, three per group. The statistics go per tile to tileInfo
// and tileStats and are summed on the CPU (readCounts): same-address atomics from every group bound the pass.
BL_STORAGE_BUFFER(3) Counts { uint counts[24]; } count;
// The counts the next classification adds to (the previous one's): zeroed here, so that no clear, and no barrier
// after it, precede the pass.
BL_STORAGE_BUFFER(4) NextCounts { uint counts[24]; } nextCount;
BL_IMAGE(0, r32ui) uniform readonly uimage2D history;
BL_IMAGE(1, r32ui) uniform writeonly uimage2D counter;
BL_IMAGE(2, r32ui) uniform writeonly uimage2D tileInfo;
BL_IMAGE(3, r32ui) uniform writeonly uimage2D tileStats;  // surface, glossy, SDF rays, ray pixels: a byte each

// Per tile and quad (y · 4 + x): its screen rays, SDF rays, surfaces and glossy pixels, a byte each (a tile has 64).
shared uint quadCounts[16][16];
shared uint tileClass[16];
// The tiles' places in the group's share of each list, then the group's bases: three global atomics per group.
shared uint screenOffset[16], sdfOffset[16], denoiseOffset[16];
shared uint groupScreen, groupSdf, groupDenoise, screenBase, sdfBase, denoiseBase;

// The dice of a tile in a frame (a different stream from the random pixel's).
float dice(uvec2 tile, uint frame) { return blReflectionUnit(blReflectionHash3(uvec3(tile, frame ^ 0x9E3779B9u))); }

bool screenSpaceFirst(uint hits, uint misses, float rnd) {
    return rnd <= params.hybrid.y + float(hits) - params.hybrid.x * float(misses);
}

void main() {
    uvec2 local = gl_LocalInvocationID.xy;
    uint slot = (local.y >> 2u) * 4u + (local.x >> 2u), quad = (local.y & 3u) * 4u + (local.x & 3u);
    ivec2 corner = ivec2(gl_GlobalInvocationID.xy) * 2;
    uvec2 tile = uvec2(corner) >> 3u;
    ivec2 size = ivec2(params.size.xy);
    ivec2 tiles = ivec2(params.size.zw);
    bool tileOnScreen = all(lessThan(tile, uvec2(tiles)));
    uint frame = params.frame.x;

    if (gl_LocalInvocationIndex == 0u) {
        if (gl_WorkGroupID.x == 0u && gl_WorkGroupID.y == 0u)
            for (uint i = 0u; i < 24u; ++i) nextCount.counts[i] = 0u;
        groupScreen = 0u;
        groupSdf = 0u;
        groupDenoise = 0u;
    }
    if (quad == 0u && tileOnScreen) {
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
        tileClass[slot] = c;
        // This frame's counter: the last frame's new bytes become the previous ones; the trace adds the new.
        imageStore(counter, ivec2(tile), uvec4((newHits << 16u) | (newMisses << 24u)));
    }
    // The quad's own inputs, read while the tile's first thread works. Pixel i of the quad: corner + (i & 1, i >> 1).
    uint perQuad = params.options.x;
    bool screenAllowed = params.options2.y != 0u;
    bool surface[4], glossy[4], sdfAllowed[4];
    for (uint i = 0u; i < 4u; ++i) {
        ivec2 pixel = corner + ivec2(i & 1u, i >> 1u);
        bool onScreen = all(lessThan(pixel, size));
        ivec2 p = min(pixel, size - 1);
        float depth = texelFetch(depthTexture, p, 0).r;
        float roughness = blReflectionRoughness(texelFetch(roughnessTexture, p, 0));
        surface[i] = onScreen && !blReflectionIsSky(depth);
        glossy[i] = surface[i] && roughness < params.normalScale.w;
        sdfAllowed[i] = params.options2.z != 0u && roughness < params.normalBias.w;
    }
    barrier();

    uint cls = tileClass[slot];
    // The base rays of samplesPerQuad (4: every pixel; 2: the diagonal from the corner; 1: the corner). Glossy
    // neighbours without a ray of their own take the ray's result: with 2 per quad the one across x (the one across
    // y is the other base ray's), with 1 all three.
    uint toScreen = 0u, toSdf = 0u, copyFlags[4];  // bit i: pixel i
    for (uint i = 0u; i < 4u; ++i) {
        ivec2 pixel = corner + ivec2(i & 1u, i >> 1u);
        bool baseRay = perQuad == 4u || (perQuad == 2u ? (i == 0u || i == 3u) : i == 0u);
        bool needsRay = glossy[i] && baseRay;
        uint checker = perQuad == 4u ? uint(pixel.x ^ pixel.y) & 1u : uint((pixel.x >> 1) ^ (pixel.y >> 1)) & 1u;
        bool wantsScreen = cls == 0u || (cls == 1u && checker == 0u);
        bool sdf = needsRay && sdfAllowed[i] && (!wantsScreen || !screenAllowed);
        bool screen = needsRay && screenAllowed && !sdf;
        toSdf |= sdf ? 1u << i : 0u;
        toScreen |= screen ? 1u << i : 0u;
        bool copyX = perQuad != 4u && glossy[i ^ 1u];
        bool copyY = perQuad == 1u && glossy[i ^ 2u];
        bool copyXY = perQuad == 1u && glossy[i ^ 3u];
        copyFlags[i] = (copyX ? 1u : 0u) | (copyY ? 2u : 0u) | (copyXY ? 4u : 0u);
    }
    uint surfaces = 0u, glossies = 0u;
    for (uint i = 0u; i < 4u; ++i) {
        surfaces += surface[i] ? 1u : 0u;
        glossies += glossy[i] ? 1u : 0u;
    }
    quadCounts[slot][quad] = bitCount(toScreen) | (bitCount(toSdf) << 8u) | (surfaces << 16u) | (glossies << 24u);
    barrier();

    // The counts of the quads before this one (bytes never carry: a tile has 64 pixels), and the tile's.
    uint before = 0u, total = 0u;
    for (uint q = 0u; q < 16u; ++q) {
        uint c = quadCounts[slot][q];
        before += q < quad ? c : 0u;
        total += c;
    }
    uint rays = total & 0xFFu, padded = (rays + 31u) & ~31u, sdfRays = (total >> 8u) & 0xFFu;
    if (quad == 0u && tileOnScreen) {
        screenOffset[slot] = padded > 0u ? atomicAdd(groupScreen, padded) : 0u;
        sdfOffset[slot] = sdfRays > 0u ? atomicAdd(groupSdf, sdfRays) : 0u;
        denoiseOffset[slot] = rays + sdfRays > 0u ? atomicAdd(groupDenoise, 1u) : 0u;
        imageStore(tileInfo, ivec2(tile), uvec4(cls | (rays << 8u) | (sdfRays << 16u)));
        imageStore(tileStats, ivec2(tile), uvec4(((total >> 16u) & 0xFFu) | ((total >> 24u) << 8u) | (sdfRays << 16u) | ((rays + sdfRays) << 24u)));
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        screenBase = groupScreen > 0u ? atomicAdd(count.counts[9], groupScreen) : 0u;
        sdfBase = groupSdf > 0u ? atomicAdd(count.counts[11], groupSdf) : 0u;
        denoiseBase = groupDenoise > 0u ? atomicAdd(count.counts[12], groupDenoise) : 0u;
    }
    barrier();
    if (!tileOnScreen) return;
    if (quad == 0u && rays + sdfRays > 0u) denoiseList.denoiseTiles[denoiseBase + denoiseOffset[slot]] = ((tile.y * 8u) << 16u) | (tile.x * 8u);
    uint tileScreen = screenBase + screenOffset[slot];
    uint screenAt = tileScreen + (before & 0xFFu), sdfAt = sdfBase + sdfOffset[slot] + ((before >> 8u) & 0xFFu);
    for (uint i = 0u; i < 4u; ++i) {
        uint record = blReflectionPack(uvec2(corner + ivec2(i & 1u, i >> 1u)), copyFlags[i]);
        if ((toScreen & (1u << i)) != 0u) screenList.screenRays[screenAt++] = record;
        if ((toSdf & (1u << i)) != 0u) sdfList.sdfRays[sdfAt++] = record;
    }
    // The helper entries that pad the tile's screen rays to a multiple of 32.
    for (uint h = quad; h < padded - rays; h += 16u) screenList.screenRays[tileScreen + rays + h] = kReflectionHelper;
}
