// The voxelization fragment shader (vct::Clipmap::voxelizationState). An application that voxelizes emittance
// writes a fragment shader of three lines and compiles it with bricklight_add_shaders:
//
//     #version 450
//     #extension GL_GOOGLE_include_directive : require
//     #include "bricklight/voxelize.glsl"
//     vec3 blVoxelEmittance(BlVoxelFragment f) { return /* light the surface sends: direct × albedo + emission */; }
//
// blVoxelEmittance returns the radiance leaving the surface's front side (the side its normal points to) at
// f.position; it may read the application's own resources (constants slots 0–2, textures, read buffers 0–6,
// storage buffers 0–5, images 0–6). It runs once per covered pixel of the projection (twice for two-sided
// materials, the second time with the normal flipped). Define BL_VOXEL_OPACITY_ONLY before the include for a
// shader without emittance (our vct/voxelize_opacity.frag is that).
//
// Per pixel: the pixel's square is tested against the triangle's edges (conservatively: any overlap counts),
// every voxel along the projection axis that the triangle's plane crosses within the square (and the triangle's
// own depth range, widened behind the surface by the material's thickness) becomes opaque; emittance goes to the voxel of each of
// 4 × 4 samples inside the triangle (edges owned by one side only, so that shared edges count once), weighted
// by the surface area it stands for and split over the six directions by the face normal; what leaves along
// the projection axis goes to the column's outermost voxel on that side and the one behind it.
#ifndef BRICKLIGHT_VOXELIZE_GLSL
#define BRICKLIGHT_VOXELIZE_GLSL

#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"

struct BlVoxelFragment {
    vec3 position;    // world space, the pixel's centre on the triangle's plane
    vec3 normal;      // the application's normal, interpolated and normalized (flipped for a back side)
    vec4 user0, user1;
    uint level;       // the clip-map level being written
    float voxelSize;  // that level's voxel size in world units
};

#ifndef BL_VOXEL_OPACITY_ONLY
vec3 blVoxelEmittance(BlVoxelFragment f);
#endif

BL_VCT_FRAME_BLOCK(7);
#define BL_VCT_FRAME_DECLARED
BL_STORAGE_BUFFER(6) BlVctEmittance { uint words[]; } blVctEmittance;
BL_STORAGE_BUFFER(7) BlVctCounters { uint counts[]; } blVctCounters;
BL_IMAGE(7, r32ui) uniform coherent uimage3D blVctOpacity;

layout(location = 0) in vec3 blVoxelNormalGs;
layout(location = 1) in vec4 blVoxelUser0Gs;
layout(location = 2) in vec4 blVoxelUser1Gs;
layout(location = 3) flat in vec4 blVoxelEdge0;
layout(location = 4) flat in vec4 blVoxelEdge1;
layout(location = 5) flat in vec4 blVoxelEdge2;
layout(location = 6) flat in vec4 blVoxelPlane;
layout(location = 7) flat in vec4 blVoxelBounds;
layout(location = 8) flat in vec4 blVoxelDepth;
layout(location = 9) flat in ivec4 blVoxelLevelAxis;
layout(location = 10) flat in vec3 blVoxelFaceNormal;
layout(location = 11) flat in ivec3 blVoxelOffset;

const int BL_VOXEL_MAX_SPAN = 6;  // voxels one pixel can cover along the axis: 3 for the plane, +2 for thickness

#ifdef BL_VOXEL_MULTI_BOUNCE
// Multiple bounces: define BL_VOXEL_MULTI_BOUNCE before the include, add Clipmap::traceBindings() to the draw
// (textures 8..14), and the emittance function may add albedo × blVoxelIndirect(f): the diffuse light (irradiance
// / π) at the fragment from the previous frame's traced volumes, six cones over its normal's hemisphere. Each
// frame then carries light one bounce further (revoxelize every frame: ClipmapDesc::persistent = false).
// Define BL_VOXEL_CONE_SURFACE(origin, direction) to a function of yours giving the world distance to the first
// surface along a cone's axis (0: unknown; e.g. a ray through your BVH or bricklight/trace.glsl) and the cones
// stop there (BlCone::surfaceDistance), so light does not leak through thin walls from bounce to bounce.
#include "bricklight/cone_trace.glsl"

vec3 blVoxelIndirect(BlVoxelFragment f) {
    vec3 n = f.normal;
    vec3 helper = abs(n.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangent = normalize(cross(helper, n));
    vec3 bitangent = cross(n, tangent);
    const uint cones = 6u;
    float factor = blConeFactor(2.0 * acos(1.0 - 1.0 / float(cones)));
    vec3 sum = vec3(0.0);
    for (uint k = 0u; k < cones; ++k) {
        float u = (float(k) + 0.5) / float(cones);
        float phi = float(k) * 2.39996323;
        vec3 d = normalize(sqrt(u) * (cos(phi) * tangent + sin(phi) * bitangent) + sqrt(1.0 - u) * n);
        BlCone c = blDefaultCone(f.position + n * (2.0 * f.voxelSize), d, factor);
        c.firstSampleT = 0.0;
#ifdef BL_VOXEL_CONE_SURFACE
        c.surfaceDistance = BL_VOXEL_CONE_SURFACE(c.origin, d);
#endif
        sum += blTraceCone(c).radiance;
    }
    return sum / float(cones);
}
#endif

void blVoxelCount(uint counter, uint amount) {
    if (blVctFrame.flags.x != 0u && amount != 0u) atomicAdd(blVctCounters.counts[counter], amount);
}

// Back from the projection's (u, v, w) to level coordinates.
ivec3 blVoxelUnproject(ivec3 q, int axis) { return axis == 0 ? q.zxy : (axis == 1 ? q.yzx : q); }
vec3 blVoxelUnproject(vec3 q, int axis) { return axis == 0 ? q.zxy : (axis == 1 ? q.yzx : q); }

// Inside for a sample: strictly inside, or on an edge that faces up-left (so that a shared edge belongs to one
// of its two triangles).
float blVoxelEdge(vec4 edge, vec2 s) {
    precise float e = edge.x * (s.x - edge.z) + edge.y * (s.y - edge.w);
    return e;
}

bool blVoxelOwns(vec4 edge, vec2 s) {
    float e = blVoxelEdge(edge, s);
    return e > 0.0 || (e == 0.0 && (edge.x > 0.0 || (edge.x == 0.0 && edge.y > 0.0)));
}

bool blVoxelWritable(uint level, ivec3 voxel, uint resolution, uint boxCount, out uint reason) {
    reason = 0u;
    if (level > 0u) {
        ivec3 finerLo = blVctFrame.origin[level - 1u].xyz >> 1;
        if (all(greaterThanEqual(voxel, finerLo)) && all(lessThan(voxel, finerLo + int(resolution / 2u)))) {
            reason = BL_VCT_COUNT_KILLED_BY_FINER;
            return false;
        }
    }
    for (uint b = 0u; b < boxCount; ++b) {
        BlVctBox box = blVctFrame.boxes[b];
        if (uint(box.minLevel.w) == level && all(greaterThanEqual(voxel, box.minLevel.xyz)) && all(lessThan(voxel, box.max.xyz)))
            return true;
    }
    reason = BL_VCT_COUNT_KILLED_NOT_DIRTY;
    return false;
}

// Each axis's opacity becomes the largest written, whatever the order (compare-and-swap on the packed word; each
// retry follows another writer's increase, so the loop ends). Most fragments find the voxel already at least as
// opaque and leave with a plain load: many small triangles share a voxel, and atomics on one word serialize.
void blVoxelMaxOpacity(ivec3 texel, uint opacity) {
    uint seen = imageLoad(blVctOpacity, texel).x;
    for (int i = 0; i < 64; ++i) {
        uint merged = vctMaxOpacity(seen, opacity);
        if (merged == seen) return;
        uint before = imageAtomicCompSwap(blVctOpacity, texel, seen, merged);
        if (before == seen) return;
        seen = before;
    }
}

void main() {
    blVoxelCount(BL_VCT_COUNT_FRAGMENTS, 1u);
    ivec2 pixelInLevel = ivec2(floor(gl_FragCoord.xy));
    // The triangle's frame (see vct/voxelize.geom): integer offsets, so these are exact.
    vec2 pixel = vec2(pixelInLevel - blVoxelOffset.xy);
    vec2 centre = pixel + 0.5;
    // Does the pixel's square touch the triangle? Its bounding box first, then each edge at the square's corner
    // furthest inside.
    bool touches = pixel.x + 1.0 >= blVoxelBounds.x && pixel.x <= blVoxelBounds.z && pixel.y + 1.0 >= blVoxelBounds.y &&
                   pixel.y <= blVoxelBounds.w;
    touches = touches && blVoxelEdge(blVoxelEdge0, centre) + 0.5 * (abs(blVoxelEdge0.x) + abs(blVoxelEdge0.y)) >= 0.0;
    touches = touches && blVoxelEdge(blVoxelEdge1, centre) + 0.5 * (abs(blVoxelEdge1.x) + abs(blVoxelEdge1.y)) >= 0.0;
    touches = touches && blVoxelEdge(blVoxelEdge2, centre) + 0.5 * (abs(blVoxelEdge2.x) + abs(blVoxelEdge2.y)) >= 0.0;
    if (!touches) {
        blVoxelCount(BL_VCT_COUNT_OFF_TRIANGLE, 1u);
        return;
    }

    uint level = uint(blVoxelLevelAxis.x);
    int axis = blVoxelLevelAxis.y;
    uint resolution = blVctFrame.params.x;
    uint boxCount = blVctFrame.params.w;
    ivec3 origin = blVctFrame.origin[level].xyz;
    // The depths the plane takes over the square, within the triangle's own range, widened by the thickness.
    precise float wCentre = blVoxelPlane.x + blVoxelPlane.y * centre.x + blVoxelPlane.z * centre.y;
    float wSpread = 0.5 * (abs(blVoxelPlane.y) + abs(blVoxelPlane.z));
    // Thickness goes behind the surface (away from the side its normal says is the front), so that no opaque,
    // dark voxel lies in front of the voxel that holds its light; a two-sided surface grows half each way.
    float facing = dot(blVoxelFaceNormal, blVoxelNormalGs) >= 0.0 ? 1.0 : -1.0;
    bool frontIsUp = facing * blVoxelFaceNormal[axis] > 0.0;  // the front looks towards +w
    float behind = blVoxelLevelAxis.z != 0 ? 0.5 : (frontIsUp ? 1.0 : 0.0);
    float wLo = max(wCentre - wSpread, blVoxelDepth.x) - behind * blVoxelDepth.z;
    float wHi = min(wCentre + wSpread, blVoxelDepth.y) + (1.0 - behind) * blVoxelDepth.z;
    int k0 = max(int(floor(wLo)) + blVoxelOffset.z, 0);
    int k1 = min(min(int(floor(wHi)) + blVoxelOffset.z, int(resolution) - 1), k0 + BL_VOXEL_MAX_SPAN - 1);

    uint opacity = vctPackOpacity(blVoxelDepth.w * abs(blVoxelFaceNormal));
    uint writable = 0u;  // bit k - k0
    uint written = 0u, killedByFiner = 0u, killedNotDirty = 0u;
    for (int k = k0; k <= k1; ++k) {
        ivec3 voxel = origin + blVoxelUnproject(ivec3(pixelInLevel, k), axis);
        uint reason;
        if (!blVoxelWritable(level, voxel, resolution, boxCount, reason)) {
            killedByFiner += reason == BL_VCT_COUNT_KILLED_BY_FINER ? 1u : 0u;
            killedNotDirty += reason == BL_VCT_COUNT_KILLED_NOT_DIRTY ? 1u : 0u;
            continue;
        }
        writable |= 1u << uint(k - k0);
        blVoxelMaxOpacity(vctTexel(level, voxel, resolution), opacity);
        ++written;
    }
    blVoxelCount(BL_VCT_COUNT_VOXELS_WRITTEN, written);
    blVoxelCount(BL_VCT_COUNT_KILLED_BY_FINER, killedByFiner);
    blVoxelCount(BL_VCT_COUNT_KILLED_NOT_DIRTY, killedNotDirty);

#ifndef BL_VOXEL_OPACITY_ONLY
    uint channels = blVctFrame.params.z;  // 0 (opacity only), 3 (isotropic) or 18 (six directions)
    if (writable == 0u || channels == 0u) return;
    // Emittance: the samples inside the triangle, counted per voxel along the axis.
    uint samples[BL_VOXEL_MAX_SPAN] = uint[BL_VOXEL_MAX_SPAN](0u, 0u, 0u, 0u, 0u, 0u);
    uint inside = 0u;
    for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
            vec2 s = pixel + (vec2(sx, sy) + 0.5) * 0.25;
            if (!blVoxelOwns(blVoxelEdge0, s) || !blVoxelOwns(blVoxelEdge1, s) || !blVoxelOwns(blVoxelEdge2, s)) continue;
            precise float w = clamp(blVoxelPlane.x + blVoxelPlane.y * s.x + blVoxelPlane.z * s.y, blVoxelDepth.x, blVoxelDepth.y);
            int k = int(floor(w)) + blVoxelOffset.z - k0;
            ++inside;  // every sample in the triangle counts, whatever this update may write (see below)
            if (k >= 0 && k < BL_VOXEL_MAX_SPAN) ++samples[k];
        }
    if (inside == 0u) return;

    float voxelSize = blVctFrame.scales.x * float(1u << level);
    vec3 local = blVoxelUnproject(vec3(centre, wCentre) + vec3(blVoxelOffset), axis);
    BlVoxelFragment f;
    f.position = (vec3(origin) + local) * voxelSize;
    vec3 normal = blVoxelNormalGs;
    f.normal = dot(normal, normal) > 0.0 ? normalize(normal) : blVoxelFaceNormal;
    f.user0 = blVoxelUser0Gs;
    f.user1 = blVoxelUser1Gs;
    f.level = level;
    f.voxelSize = voxelSize;
    // The front side is where the application's normal points; the face normal, so oriented, splits the light.
    vec3 front = dot(blVoxelFaceNormal, f.normal) >= 0.0 ? blVoxelFaceNormal : -blVoxelFaceNormal;
    uint directions = channels / 3u;
    int sides = 1 + blVoxelLevelAxis.z;
    // Fixed-point units per unit radiance, × the area each sample stands for (1/16 of a voxel face, divided by
    // the projection's cosine).
    // precise (no fused multiply-adds) here and in the geometry stage: Vulkan and GL then round alike and write
    // the same words.
    precise float unitsPerSample = blVctFrame.scales.y * blVoxelPlane.w / 16.0;
    uint emittanceWrites = 0u;
    for (int side = 0; side < sides; ++side) {
        BlVoxelFragment g = f;
        g.normal = side == 0 ? f.normal : -f.normal;
        vec3 facing = side == 0 ? front : -front;
        vec3 radiance = blVoxelEmittance(g);
        // Negative and NaN light adds nothing; one fragment adds at most FP16's largest value.
        radiance = mix(vec3(0.0), min(radiance, vec3(65504.0)), greaterThan(radiance, vec3(0.0)));
        for (uint d = 0u; d < directions; ++d) {
            precise float weight = directions == 1u ? 1.0 : max(dot(facing, vctDirection(d)), 0.0);
            if (weight == 0.0) continue;
            // Light leaving along the projection axis goes to the column's last voxel on that side and the one
            // behind it, so that no voxel of the same column (thickness, or a tilted plane's spread) covers it and
            // a filtered sample between the two still sees the surface's radiance; light leaving sideways stays
            // in each sample's own voxel.
            // The column's ends come from the geometry alone (not from what this update may write), so that a
            // voxel gets the same light whichever update writes it.
            bool axial = directions > 1u && d % 3u == uint(axis);
            int end = d < 3u ? k1 - k0 : 0;
            int behind = d < 3u ? end - 1 : end + 1;
            for (int k = 0; k < BL_VOXEL_MAX_SPAN; ++k) {
                uint count = axial ? ((k == end || (k == behind && behind <= k1 - k0)) ? inside : 0u) : samples[k];
                if (count == 0u || (writable & (1u << uint(k))) == 0u) continue;
                ivec3 voxel = origin + blVoxelUnproject(ivec3(pixelInLevel, k0 + k), axis);
                uint texel = vctTexelIndex(level, voxel, resolution);
                uint texelCount = resolution * resolution * resolution * blVctFrame.params.y;
                precise vec3 amount = radiance * (weight * float(count) * unitsPerSample);
                uvec3 units = uvec3(min(amount + 0.5, vec3(4.0e9)));
                for (uint c = 0u; c < 3u; ++c)
                    if (units[c] != 0u) atomicAdd(blVctEmittance.words[vctWordIndex(texel, d * 3u + c, texelCount)], units[c]);
                ++emittanceWrites;
            }
        }
    }
    blVoxelCount(BL_VCT_COUNT_EMITTANCE_WRITES, emittanceWrites);
#endif
}

#endif
