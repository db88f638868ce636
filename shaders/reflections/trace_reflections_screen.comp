#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Screen-space reflections (reflections::ReflectionClassifier::traceScreenSpace): dispatched indirectly over the padded
// screen-space list, 32 entries a group, all of one tile. Each ray (bricklight/reflection_ray.glsl's, the same the SDF
// pass traces) marches the min/max depth pyramid in (pixel, depth) space, where a ray stays a straight line: a cell
// whose closest depth lies behind the ray's stretch through it, or whose farthest lies more than `thickness` (a
// fraction of its distance from the camera) in front of it, is skipped a level coarser; otherwise the march refines, and a pixel the ray reaches within the
// thickness is the hit. A hit facing the ray, away from the screen's edges and seen by the previous camera takes
// its radiance from the previous frame's lit image; the rest go on to the SDF list. Each group adds the pixels its
// rays resolved and missed to its tile's hit counter (shared-memory sums, one atomic).
layout(local_size_x = 32, local_size_y = 1, local_size_z = 1) in;

#include "reflection_params.glsl"
#include "bricklight/reflection_ray.glsl"  // the ray GiContext::traceReflectionRays continues
BL_TEXTURE(0) uniform sampler2D depthTexture;
BL_TEXTURE(1) uniform sampler2D normalTexture;
BL_TEXTURE(2) uniform sampler2D roughnessTexture;
BL_TEXTURE(3) uniform sampler2D depthPyramid;  // RG32F: min, max depth
BL_TEXTURE(4) uniform sampler2D previousLit;   // bilinear
BL_READ_BUFFER(1) ScreenList { uint screenRays[]; } screenList;
BL_STORAGE_BUFFER(0) SdfList { uint sdfRays[]; } sdfList;
BL_STORAGE_BUFFER(1) Counts { uint counts[24]; } count;  // 9: screen entries, 11: SDF rays
BL_IMAGE(0, rgba16f) uniform writeonly image2D outputImage;
BL_IMAGE(1, r32ui) uniform uimage2D counter;
BL_IMAGE(2, r32ui) uniform uimage2D tileInfo;

shared uint hitWeight, missWeight, hitRays, missRays, missBase;

const float kFar = 1.0e30;

// (pixel x, pixel y, near-small depth) of a world point; w ≤ 0 behind the camera.
vec4 toScreen(vec3 world) {
    vec4 clip = params.viewProjection * vec4(world, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    return vec4((ndc.xy * 0.5 + 0.5) * vec2(params.size.xy), blReflectionNearSmall(ndc.z), clip.w);
}

// Parameter (in pixels along the screen-space ray) where it leaves the box [lo, hi] in xy.
float exitT(vec3 start, vec3 d, vec2 lo, vec2 hi) {
    vec2 bound = mix(lo, hi, greaterThan(d.xy, vec2(0.0)));
    vec2 t = mix(vec2(kFar), (bound - start.xy) / d.xy, greaterThan(abs(d.xy), vec2(1.0e-8)));
    return min(t.x, t.y);
}

// Marches from the pixel `origin` (its centre and near-small depth) along d (|d.xy| = 1 pixel). Hit: the
// parameter of the hit and the ray's distance behind the surface there (world units along the view).
bool march(vec3 origin, vec3 d, float tMax, out float tHit, out float behind) {
    vec2 size = vec2(params.size.xy);
    int maxLevel = int(params.trace.y) - 1;
    float thickness = params.trace2.x;
    bool reversed = params.options.w != 0u;
    // Start beyond the origin's own pixel.
    float t = exitT(origin, d, floor(origin.xy), floor(origin.xy) + 1.0) + 1.0e-3;
    int level = 0;
    tHit = 0.0;
    behind = 0.0;
    for (uint i = 0u; i < params.trace.x && t < tMax; ++i) {
        vec3 s = origin + d * t;
        // The mip's extent by the pyramid's rule (depth_pyramid.h), not textureSize: llvmpipe answers textureSize
        // with one lane's level for all the lanes of a SIMD group, and the levels here differ from lane to lane.
        ivec2 extent = max(ivec2(params.size.xy) >> level, ivec2(1));
        ivec2 cell = min(ivec2(s.xy) >> level, extent - 1);
        vec2 lo = vec2(cell << level);
        vec2 hi = mix(vec2((cell + 1) << level), size, equal(cell, extent - 1));
        float tExit = min(exitT(origin, d, lo, hi), tMax);
        vec2 minMax = texelFetch(depthPyramid, cell, level).rg;
        float closest = reversed ? 1.0 - minMax.g : minMax.r;
        float farthest = reversed ? 1.0 - minMax.r : minMax.g;
        float zIn = s.z, zOut = origin.z + d.z * tExit;
        float segmentNear = min(zIn, zOut), segmentFar = max(zIn, zOut);
        bool inFront = segmentFar < closest;
        float farthestDistance = blReflectionViewDistance(farthest);
        bool behindAll = blReflectionViewDistance(segmentNear) > farthestDistance * (1.0 + thickness);
        if (inFront || behindAll) {
            t = tExit + 1.0e-3;
            level = min(level + 1, maxLevel);
            continue;
        }
        // The ray reaches the cell's closest depth here (or is already past it).
        float tReach = zIn < closest && d.z > 0.0 ? min(t + (closest - zIn) / d.z, tExit) : t;
        if (level > 0) {
            t = tReach;
            --level;
            continue;
        }
        tHit = tReach;
        // How far behind the surface, in thicknesses (a fraction of the surface's distance: scale-free).
        float closestDistance = blReflectionViewDistance(closest);
        behind = max(blReflectionViewDistance(origin.z + d.z * tReach) - closestDistance, 0.0) / max(thickness * closestDistance, 1.0e-30);
        return true;
    }
    return false;
}

void main() {
    uint lane = gl_LocalInvocationID.x;
    uint index = gl_WorkGroupID.x * 32u + lane;
    if (lane == 0u) {
        hitWeight = 0u;
        missWeight = 0u;
        hitRays = 0u;
        missRays = 0u;
    }
    barrier();

    uint entry = index < count.counts[9] ? screenList.screenRays[index] : kReflectionHelper;
    uvec2 pixel = blReflectionPixel(entry);
    bool valid = entry != kReflectionHelper && all(lessThan(pixel, params.size.xy));
    uint copyFlags = entry >> 29u;
    ivec2 size = ivec2(params.size.xy);
    ivec2 p = min(ivec2(pixel), size - 1);
    float depth = texelFetch(depthTexture, p, 0).r;
    vec3 normal = blReflectionNormal(texelFetch(normalTexture, p, 0));
    float roughness = blReflectionRoughness(texelFetch(roughnessTexture, p, 0));
    vec2 centre = vec2(p) + 0.5;
    vec3 world = blReflectionWorldPosition(centre, depth);
    vec3 toViewer = blReflectionToViewer(centre, world);
    if (dot(normal, toViewer) < 0.0) normal = -normal;  // as the SDF pass: the side the camera sees
    vec3 rayDirection = blReflectionDirection(pixel, params.frame.x, normal, toViewer, roughness);

    // The ray on screen: a straight line in (pixel, depth). Its far end is kept in front of the camera (w > 0).
    vec3 origin = vec3(centre, blReflectionNearSmall(depth));
    vec4 start = toScreen(world);
    float reach = max(length(blReflectionWorldPosition(centre, params.options.w != 0u ? 1.0 : 0.0) - world), 1.0e-3);
    vec4 end = toScreen(world + rayDirection * reach);
    float shrink = end.w < 0.1 * start.w ? 0.9 * start.w / max(start.w - end.w, 1.0e-20) : 1.0;
    end = toScreen(world + rayDirection * reach * shrink);
    vec3 d = end.xyz - start.xyz;
    float screenLength = length(d.xy);
    bool marchable = valid && screenLength > 1.0e-4;
    d /= max(screenLength, 1.0e-20);
    // Where it leaves the screen or the depth range.
    float tMax = exitT(origin, d, vec2(0.0), vec2(size));
    tMax = min(tMax, d.z > 0.0 ? (1.0 - origin.z) / d.z : (d.z < 0.0 ? -origin.z / d.z : kFar));

    float tHit = 0.0, behind = 0.0;
    bool hit = marchable && march(origin, d, tMax, tHit, behind);
    vec3 s = origin + d * tHit;
    ivec2 hitPixel = clamp(ivec2(s.xy), ivec2(0), size - 1);
    float hitDepth = texelFetch(depthTexture, hitPixel, 0).r;
    vec3 hitNormal = blReflectionNormal(texelFetch(normalTexture, hitPixel, 0));
    vec3 hitWorld = blReflectionWorldPosition(vec2(hitPixel) + 0.5, hitDepth);
    vec4 previousClip = params.previousViewProjection * vec4(hitWorld, 1.0);
    vec2 previousUv = previousClip.xy / max(previousClip.w, 1.0e-20) * 0.5 + 0.5;
    vec2 uv = s.xy / vec2(size);
    float edge = min(min(uv.x, 1.0 - uv.x), min(uv.y, 1.0 - uv.y));
    float confidence = params.trace2.y > 0.0 ? clamp(edge / params.trace2.y, 0.0, 1.0) : 1.0;
    confidence *= clamp(2.0 - 2.0 * behind, 0.0, 1.0);  // full up to half the thickness
    bool facing = dot(hitNormal, rayDirection) < 0.0;
    bool seenBefore = previousClip.w > 0.0 && all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThanEqual(previousUv, vec2(1.0)));
    bool resolved = hit && facing && seenBefore && confidence >= params.trace2.z;
    vec3 radiance = textureLod(previousLit, previousUv, 0.0).rgb;

    if (valid && resolved) {
        vec4 value = vec4(radiance, 1.0);
        imageStore(outputImage, p, value);
        ivec2 q = p ^ ivec2(1, 0);
        if ((copyFlags & 1u) != 0u) imageStore(outputImage, q, value);
        q = p ^ ivec2(0, 1);
        if ((copyFlags & 2u) != 0u) imageStore(outputImage, q, value);
        q = p ^ ivec2(1, 1);
        if ((copyFlags & 4u) != 0u) imageStore(outputImage, q, value);
    }
    uint weight = 1u + bitCount(copyFlags);
    uint missIndex = 0u;
    bool toSdf = valid && !resolved && params.options2.z != 0u;
    if (valid && resolved) {
        atomicAdd(hitWeight, weight);
        atomicAdd(hitRays, 1u);
    }
    if (valid && !resolved) atomicAdd(missWeight, weight);
    if (toSdf) missIndex = atomicAdd(missRays, 1u);
    barrier();

    // Entry 0 of a group is always a ray (helpers only pad a tile's last group): it names the group's tile.
    uint first = index - lane < count.counts[9] ? screenList.screenRays[index - lane] : kReflectionHelper;
    if (lane == 0u && first != kReflectionHelper) {
        ivec2 tile = ivec2(blReflectionPixel(first) / 8u);
        // A tile's pixels count once each (≤ 64), and the classifier zeroed the new bytes: no byte overflows.
        imageAtomicAdd(counter, tile, min(hitWeight, 255u) | (min(missWeight, 255u) << 8u));
        // The tile's SDF rays grow by the misses; its resolved rays go to the top byte (readCounts sums them).
        imageAtomicAdd(tileInfo, tile, (missRays << 16u) | (hitRays << 24u));
        missBase = missRays > 0u ? atomicAdd(count.counts[11], missRays) : 0u;
    }
    barrier();
    if (toSdf) sdfList.sdfRays[missBase + missIndex] = entry;
}
