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
// storage buffers 0–6, images 0–6). It runs once per covered pixel of the projection (twice for two-sided
// materials, the second time with the normal flipped). Define BL_VOXEL_OPACITY_ONLY before the include for a
// shader without emittance (our vct/voxelize_opacity.frag is that).
//
// Alpha-tested materials (foliage cards): define BL_VOXEL_COVERAGE before the include and give
//
//     float blVoxelCoverage(BlVoxelFragment f) { return /* 1 where the surface is, 0 where it is cut out */; }
//
// (e.g. the material's alpha test at f.user0's texture coordinates). It is evaluated at 16 points of each
// pixel's square (see blVoxelPixelCoverage) and the voxels the pixel writes take the material's opacity times
// their mean; the pixel's light is weighted by it too. Results outside [0, 1] are clamped, NaN counts as 1 (as
// without the hook). Without the define nothing changes: opaque materials write the same words as before.
//
// Per pixel: the pixel's square is tested against the triangle's edges (conservatively: any overlap counts),
// every voxel along the projection axis that the triangle's plane crosses within the square (and the triangle's
// own depth range, widened behind the surface by the material's thickness) becomes opaque; emittance goes to the voxel of each of
// 4 × 4 samples inside the triangle (edges owned by one side only, so that shared edges count once), weighted
// by the surface area it stands for and split over the six directions by the face normal; what leaves along
// the projection axis goes to the column's outermost voxel on that side and the one behind it.
//
// The same code serves three stages: our geometry shader (vct/voxelize.geom) defines BL_VOXEL_SETUP_ONLY and
// takes the per-triangle setup (blVoxelSetupTriangle); the fragment main below and the compute voxelizer of
// registered meshes (bricklight/voxelize_compute.glsl, which defines BL_VOXEL_COMPUTE) both run the per-pixel
// body (blVoxelPixel), so that the two paths write the same words.
#ifndef BRICKLIGHT_VOXELIZE_GLSL
#define BRICKLIGHT_VOXELIZE_GLSL

#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"

BL_VCT_FRAME_BLOCK(7);
#define BL_VCT_FRAME_DECLARED

// One triangle projected into one level: what the geometry stage hands the fragment stage as flat values.
// Edges, plane, bounds and depth range are in the triangle's frame, `offset` voxels from the level's origin.
struct BlVoxelTriangle {
    vec4 edge[3];      // xy unit inward normal n, zw a point p; n·(x − p) ≥ 0 inside
    vec4 plane;        // depth w = x + y·u + z·v; w: surface area per projected area
    vec4 bounds;       // the triangle's (u, v) bounding box: min xy, max zw
    vec4 depth;        // x, y: the triangle's depth range; z thickness; w opacity
    ivec4 levelAxis;   // x level, y projection axis, z two-sided
    vec3 faceNormal;   // unit geometric normal in world space (winding order)
    ivec3 offset;      // the triangle's frame in the level, projected (u, v, w)
    vec3 opposite;     // edge function of each vertex on its opposite edge (barycentric weights; not passed on)
};

// (u, v, w): the two projected coordinates and the depth along `axis`.
vec3 blVoxelProject(vec3 p, int axis) { return axis == 0 ? p.yzx : (axis == 1 ? p.zxy : p); }

// The triangle (world space) in level `level`: false where it is dropped there (non-finite, outside the level,
// wholly inside the finer level, or degenerate). material: x thickness, y opacity, z two-sided (VoxelMaterial).
bool blVoxelSetupTriangle(vec3 world[3], uint level, vec4 material, out BlVoxelTriangle t) {
    t = BlVoxelTriangle(vec4[3](vec4(0.0), vec4(0.0), vec4(0.0)), vec4(0.0), vec4(0.0), vec4(0.0), ivec4(0), vec3(0.0), ivec3(0), vec3(0.0));
    if (level >= blVctFrame.params.y) return false;
    float resolution = float(blVctFrame.params.x);
    float voxelSize = blVctFrame.scales.x * float(1u << level);
    // The triangle in its own frame: voxel units relative to the voxel of its first vertex. Everything the
    // per-pixel body tests is computed there, so that a triangle gives bit-identical results wherever the level
    // lies (a scrolled clip-map equals one voxelized from scratch); `offset` (integer) places that frame in the
    // level.
    vec3 pv[3];
    for (int i = 0; i < 3; ++i) pv[i] = world[i] / voxelSize;
    // Non-finite or absurdly distant vertices would make every edge test meaningless: drop the triangle.
    for (int i = 0; i < 3; ++i)
        if (any(isnan(pv[i])) || any(greaterThan(abs(pv[i]), vec3(1.0e8)))) return false;
    vec3 base = floor(pv[0]);
    ivec3 offset = ivec3(base) - blVctFrame.origin[level].xyz;
    vec3 p[3];
    for (int i = 0; i < 3; ++i) p[i] = pv[i] - base;
    if (any(greaterThan(abs(p[1]), vec3(1.0e7))) || any(greaterThan(abs(p[2]), vec3(1.0e7)))) return false;

    float thickness = clamp(material.x, 0.0, 2.0);
    float pad = 1.0 + 0.5 * thickness;
    vec3 lo = min(min(p[0], p[1]), p[2]) + vec3(offset), hi = max(max(p[0], p[1]), p[2]) + vec3(offset);
    if (any(greaterThan(lo, vec3(resolution + pad))) || any(lessThan(hi, vec3(-pad)))) return false;
    if (level > 0u) {
        // Wholly inside the finer level: those voxels come from downsampling it.
        vec3 finerLo = vec3(blVctFrame.origin[level - 1u].xyz) * 0.5 - vec3(blVctFrame.origin[level].xyz);
        vec3 finerHi = finerLo + 0.5 * resolution;
        if (all(greaterThanEqual(lo - pad, finerLo)) && all(lessThanEqual(hi + pad, finerHi))) return false;
    }

    // precise: no fused multiply-adds, so that Vulkan and GL, and the geometry and compute stages, round alike
    // (the emittance words must agree).
    precise vec3 n = cross(p[1] - p[0], p[2] - p[0]);
    vec3 an = abs(n);
    int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    vec3 q[3];
    for (int i = 0; i < 3; ++i) q[i] = blVoxelProject(p[i], axis);
    vec3 nq = blVoxelProject(n, axis);
    if (nq.z == 0.0) return false;  // degenerate: no area at float precision
    float orientation = nq.z > 0.0 ? 1.0 : -1.0;  // counter-clockwise in (u, v) when positive

    // Each edge is anchored at its lexicographically smaller end, so that the two triangles sharing an edge
    // compute exactly opposite values at any point (the per-pixel fill rule relies on it).
    for (int i = 0; i < 3; ++i) {
        vec2 a = q[i].xy, b = q[(i + 1) % 3].xy;
        precise vec2 e = orientation * vec2(a.y - b.y, b.x - a.x);
        precise float len = length(e);
        e /= len;
        t.edge[i] = vec4(e, a.x < b.x || (a.x == b.x && a.y < b.y) ? a : b);
    }
    precise vec4 plane = vec4(q[0].z + (nq.x * q[0].x + nq.y * q[0].y) / nq.z, -nq.x / nq.z, -nq.y / nq.z,
                              length(n) / abs(nq.z));
    t.plane = plane;
    vec2 uvLo = min(min(q[0].xy, q[1].xy), q[2].xy), uvHi = max(max(q[0].xy, q[1].xy), q[2].xy);
    t.bounds = vec4(uvLo, uvHi);
    t.depth = vec4(min(min(q[0].z, q[1].z), q[2].z), max(max(q[0].z, q[1].z), q[2].z), thickness, clamp(material.y, 0.0, 1.0));
    // Barycentric weights of a point: edge i is opposite vertex (i + 2) % 3.
    precise vec3 opposite = vec3(dot(t.edge[1].xy, q[0].xy - t.edge[1].zw), dot(t.edge[2].xy, q[1].xy - t.edge[2].zw),
                                 dot(t.edge[0].xy, q[2].xy - t.edge[0].zw));
    t.opposite = opposite;
    t.levelAxis = ivec4(int(level), axis, material.z != 0.0 ? 1 : 0, 0);
    precise vec3 unitNormal = n / length(n);
    t.faceNormal = unitNormal;
    t.offset = ivec3(blVoxelProject(vec3(offset), axis));
    return true;
}

// The weights of the triangle's three vertices at a point s of its (u, v) frame (extrapolated outside it).
vec3 blVoxelWeights(BlVoxelTriangle t, vec2 s) {
    vec3 weight;
    for (int i = 0; i < 3; ++i) {
        precise float e = dot(t.edge[i].xy, s - t.edge[i].zw);
        weight[(i + 2) % 3] = e / t.opposite[(i + 2) % 3];
    }
    return weight;
}

#ifndef BL_VOXEL_SETUP_ONLY

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
#ifdef BL_VOXEL_COVERAGE
float blVoxelCoverage(BlVoxelFragment f);
#endif

// How the application's user vectors change per pixel of the projection (d/du, d/dv), so that the coverage hook
// sees them at its sample points rather than at the pixel's centre: derivatives of the rasterized values in the
// fragment stage; zero in the compute voxelizer, whose user vectors are the instance's, the same at every vertex.
struct BlVoxelUserGradient {
    vec4 user0Du, user0Dv, user1Du, user1Dv;
};

// Light is summed in fixed point in entries of this pool (four words: one per colour, then the surfaces' projected
// coverage, vct_layout.glsl's VCT_COVERAGE_UNITS per voxel face) that the update's voxelization claims per voxel and
// direction; the direction's atlas word holds the entry's tagged index until
// finishVoxelization() turns the sums into radiance (vct_layout.glsl's vctTagLightEntry).
BL_STORAGE_BUFFER(6) BlVctLight { uint words[]; } blVctLight;
BL_STORAGE_BUFFER(7) BlVctCounters { uint counts[]; } blVctCounters;
// The clip-map's atlas (vct_layout.glsl): opacity words, and the directions' entry indices while the update writes.
BL_IMAGE(7, r32ui) uniform coherent uimage3D blVctAtlas;

#ifndef BL_VOXEL_COMPUTE
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
#endif

const int BL_VOXEL_MAX_SPAN = 6;  // voxels one pixel can cover along the axis: 3 for the plane, +2 for thickness

#ifdef BL_VOXEL_MULTI_BOUNCE
// Multiple bounces: define BL_VOXEL_MULTI_BOUNCE before the include, create the clip-map with
// ClipmapDesc::multiBounce, add Clipmap::bounceBindings() to the draw (textures 8 and 9), and the emittance function
// may add albedo × blVoxelIndirect(f): the diffuse light (irradiance / π) at the fragment from a copy of the
// previous frame's atlas, six cones over its normal's hemisphere. Each frame then carries light one bounce further
// (revoxelize every frame: ClipmapDesc::persistent = false).
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
        c.planeNormal = n;
        c.planeDistance = 2.0 * f.voxelSize;
        // Samples a width apart: trilinear reads at that spacing still sum a wall's opacity to its whole value,
        // and these cones run for every fragment of the voxelization (half the samples of 0.5, the same light).
        c.tracingStep = 1.0;
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
    uint seen = imageLoad(blVctAtlas, texel).x;
    for (int i = 0; i < 64; ++i) {
        uint merged = vctMaxOpacity(seen, opacity);
        if (merged == seen) return;
        uint before = imageAtomicCompSwap(blVctAtlas, texel, seen, merged);
        if (before == seen) return;
        seen = before;
    }
}

#ifndef BL_VOXEL_OPACITY_ONLY
// The pool entry of a voxel's direction (its atlas word `texel`), claimed on first touch: the entry comes from one
// of BL_VCT_LIGHT_POOLS sub-pools chosen by a hash of the texel (so that claims do not all meet on one counter),
// and a compare-and-swap installs it over the word's old radiance; a fragment that loses the race takes the winner's
// entry (its own stays unused). Most writes find the entry installed and cost one load. ~0u: the sub-pool is full
// (the light is dropped and counted).
uint blVoxelLightEntry(ivec3 texel) {
    uint word = imageLoad(blVctAtlas, texel).x;
    if (vctIsLightEntry(word)) return vctLightEntryOf(word);
    uint hash = (uint(texel.x) * 73856093u) ^ (uint(texel.y) * 19349663u) ^ (uint(texel.z) * 83492791u);
    uint pool = (hash ^ (hash >> 16u)) & (BL_VCT_LIGHT_POOLS - 1u);
    uint perPool = blVctFrame.flags.z;
    uint index = atomicAdd(blVctCounters.counts[BL_VCT_COUNTER_POOLS + pool], 1u);
    if (index >= perPool) {
        atomicAdd(blVctCounters.counts[BL_VCT_COUNT_LIGHT_DROPPED], 1u);
        return ~0u;
    }
    uint entry = pool * perPool + index;
    uint before = imageAtomicCompSwap(blVctAtlas, texel, word, vctTagLightEntry(entry));
    // Lost: only an entry replaces radiance, so the word now holds the winner's.
    return before == word ? entry : vctLightEntryOf(before);
}

// Adds fixed-point light (xyz) and projected coverage (w) to a voxel's direction: atomic adds whose results nobody
// waits for.
void blVoxelAddLight(ivec3 texel, uvec4 units) {
    uint entry = blVoxelLightEntry(texel);
    if (entry == ~0u) return;
    for (uint c = 0u; c < 4u; ++c)
        if (units[c] != 0u) atomicAdd(blVctLight.words[4u * entry + c], units[c]);
}
#endif

#ifdef BL_VOXEL_COVERAGE
// A 32-bit integer hash (a PCG step's output permutation): decorrelates the sample jitter of neighbouring pixels.
uint blVoxelHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The share of the pixel's square the material covers: the mean of blVoxelCoverage at 4 × 4 stratified points,
// each jittered inside its cell of the square.
//
// Why this method: a voxel's opacity is the largest any fragment writes (blVoxelMaxOpacity), so the coverage has
// to be settled per pixel, not summed over fragments; the mean over the pixel's square is the fraction of the
// voxel's cross-section the card blocks, which is what a directional opacity means. Sampling the whole square
// (not only the part inside this triangle) gives the two triangles of a card the same value on their shared
// diagonal, so the maximum does not bias it upwards. The jitter makes the estimate unbiased for alpha patterns
// finer than the 4 × 4 grid (a fixed grid aliases with a regular pattern: every pixel would read the same
// phase of it). It comes from a hash of the pixel's world coordinates (level, axis and the projected world
// voxel), never of the frame: a re-voxelization, a scrolled clip-map and the compute voxelizer take the same
// points, so the words are stable over frames and the two paths agree.
float blVoxelPixelCoverage(BlVoxelTriangle t, ivec2 pixelInLevel, vec2 pixel, vec3 normal, vec4 user0, vec4 user1,
                           BlVoxelUserGradient gradient) {
    uint level = uint(t.levelAxis.x);
    int axis = t.levelAxis.y;
    ivec3 origin = blVctFrame.origin[level].xyz;
    ivec3 originProjected = axis == 0 ? origin.yzx : (axis == 1 ? origin.zxy : origin);
    ivec2 world = originProjected.xy + pixelInLevel;
    uint seed = blVoxelHash(uint(world.x) ^ blVoxelHash(uint(world.y) ^ blVoxelHash(level * 3u + uint(axis))));
    float voxelSize = blVctFrame.scales.x * float(1u << level);
    vec2 centre = pixel + 0.5;
    BlVoxelFragment f;
    f.normal = normal;
    f.level = level;
    f.voxelSize = voxelSize;
    float sum = 0.0;
    for (uint i = 0u; i < 16u; ++i) {
        uint bits = blVoxelHash(seed + i);
        vec2 jitter = vec2(float(bits & 0xffffu), float(bits >> 16u)) / 65536.0;
        vec2 s = pixel + (vec2(float(i & 3u), float(i >> 2u)) + jitter) * 0.25;
        // On the triangle's plane, extended past its edges.
        precise float w = t.plane.x + t.plane.y * s.x + t.plane.z * s.y;
        precise vec3 position = (vec3(origin) + blVoxelUnproject(vec3(s, w) + vec3(t.offset), axis)) * voxelSize;
        f.position = position;
        vec2 d = s - centre;
        f.user0 = user0 + gradient.user0Du * d.x + gradient.user0Dv * d.y;
        f.user1 = user1 + gradient.user1Du * d.x + gradient.user1Dv * d.y;
        float c = blVoxelCoverage(f);
        sum += isnan(c) ? 1.0 : clamp(c, 0.0, 1.0);
    }
    return sum / 16.0;
}
#endif

// The per-pixel body: pixel `pixelInLevel` (of the level's resolution² projection) of the triangle `t`, with the
// application's attributes interpolated at the pixel's centre (and their change per pixel, for the coverage
// hook). The caller counts the fragment.
void blVoxelPixel(BlVoxelTriangle t, ivec2 pixelInLevel, vec3 interpolatedNormal, vec4 user0, vec4 user1,
                  BlVoxelUserGradient userGradient) {
    // The triangle's frame (see blVoxelSetupTriangle): integer offsets, so these are exact.
    vec2 pixel = vec2(pixelInLevel - t.offset.xy);
    vec2 centre = pixel + 0.5;
    // Does the pixel's square touch the triangle? Its bounding box first, then each edge at the square's corner
    // furthest inside.
    bool touches = pixel.x + 1.0 >= t.bounds.x && pixel.x <= t.bounds.z && pixel.y + 1.0 >= t.bounds.y &&
                   pixel.y <= t.bounds.w;
    for (int i = 0; i < 3; ++i) {
        precise float reach = blVoxelEdge(t.edge[i], centre) + 0.5 * (abs(t.edge[i].x) + abs(t.edge[i].y));
        touches = touches && reach >= 0.0;
    }
    if (!touches) {
        blVoxelCount(BL_VCT_COUNT_OFF_TRIANGLE, 1u);
        return;
    }

    uint level = uint(t.levelAxis.x);
    int axis = t.levelAxis.y;
    uint resolution = blVctFrame.params.x;
    uint boxCount = blVctFrame.params.w;
    ivec3 origin = blVctFrame.origin[level].xyz;
    // The depths the plane takes over the square, within the triangle's own range, widened by the thickness.
    precise float wCentre = t.plane.x + t.plane.y * centre.x + t.plane.z * centre.y;
    precise float wSpread = 0.5 * (abs(t.plane.y) + abs(t.plane.z));
    // Thickness goes behind the surface (away from the side its normal says is the front), so that no opaque,
    // dark voxel lies in front of the voxel that holds its light; a two-sided surface grows half each way.
    float facing = dot(t.faceNormal, interpolatedNormal) >= 0.0 ? 1.0 : -1.0;
    bool frontIsUp = facing * t.faceNormal[axis] > 0.0;  // the front looks towards +w
    float behind = t.levelAxis.z != 0 ? 0.5 : (frontIsUp ? 1.0 : 0.0);
    precise float wLo = max(wCentre - wSpread, t.depth.x) - behind * t.depth.z;
    precise float wHi = min(wCentre + wSpread, t.depth.y) + (1.0 - behind) * t.depth.z;
    int k0 = max(int(floor(wLo)) + t.offset.z, 0);
    int k1 = min(min(int(floor(wHi)) + t.offset.z, int(resolution) - 1), k0 + BL_VOXEL_MAX_SPAN - 1);

#ifdef BL_VOXEL_COVERAGE
    vec3 shadingNormal = dot(interpolatedNormal, interpolatedNormal) > 0.0 ? normalize(interpolatedNormal) : t.faceNormal;
    float coverage = blVoxelPixelCoverage(t, pixelInLevel, pixel, shadingNormal, user0, user1, userGradient);
    uint opacity = vctPackOpacity(t.depth.w * coverage * abs(t.faceNormal));
    // Nothing of the surface here: no opacity, and no light (an empty voxel carries none).
    if (opacity == 0u) return;
#else
    uint opacity = vctPackOpacity(t.depth.w * abs(t.faceNormal));
#endif
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
        blVoxelMaxOpacity(vctTexel(0u, level, voxel, resolution), opacity);
        ++written;
    }
    blVoxelCount(BL_VCT_COUNT_VOXELS_WRITTEN, written);
    blVoxelCount(BL_VCT_COUNT_KILLED_BY_FINER, killedByFiner);
    blVoxelCount(BL_VCT_COUNT_KILLED_NOT_DIRTY, killedNotDirty);

#ifndef BL_VOXEL_OPACITY_ONLY
    uint directions = blVctFrame.params.z;  // 0 (opacity only), 1 (isotropic) or 6
    if (writable == 0u || directions == 0u) return;
    // Emittance: the pixel's samples inside the triangle (edges owned by one side only, so that shared edges count
    // once) give the area of the surface it stands for; isotropic emittance also counts them per voxel along the
    // axis — voxel k's count in bits 5k..5k+4 of one word (at most 16 each): a counter array indexed by a computed k
    // is kept in memory, not in registers.
    uint samples = 0u;
    uint inside = 0u;
    for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
            vec2 s = pixel + (vec2(sx, sy) + 0.5) * 0.25;
            if (!blVoxelOwns(t.edge[0], s) || !blVoxelOwns(t.edge[1], s) || !blVoxelOwns(t.edge[2], s)) continue;
            ++inside;  // every sample in the triangle counts, whatever this update may write (see below)
            if (directions != 1u) continue;
            precise float w = clamp(t.plane.x + t.plane.y * s.x + t.plane.z * s.y, t.depth.x, t.depth.y);
            int k = int(floor(w)) + t.offset.z - k0;
            if (k >= 0 && k < BL_VOXEL_MAX_SPAN) samples += 1u << (5u * uint(k));
        }
    if (inside == 0u) return;

    float voxelSize = blVctFrame.scales.x * float(1u << level);
    vec3 local = blVoxelUnproject(vec3(centre, wCentre) + vec3(t.offset), axis);
    BlVoxelFragment f;
    f.position = (vec3(origin) + local) * voxelSize;
    vec3 normal = interpolatedNormal;
    f.normal = dot(normal, normal) > 0.0 ? normalize(normal) : t.faceNormal;
    f.user0 = user0;
    f.user1 = user1;
    f.level = level;
    f.voxelSize = voxelSize;
    // The front side is where the application's normal points; the face normal, so oriented, splits the light.
    vec3 front = dot(t.faceNormal, f.normal) >= 0.0 ? t.faceNormal : -t.faceNormal;
    int sides = 1 + t.levelAxis.z;
    // The surface area each sample stands for, in voxel faces (1/16 of one, divided by the projection's cosine).
    // precise (no fused multiply-adds) here and in the geometry stage: Vulkan and GL then round alike and write
    // the same words.
    precise float sampleArea = t.plane.w / 16.0;
#ifdef BL_VOXEL_COVERAGE
    sampleArea *= coverage;  // the light of the covered share of the pixel's surface only
#endif
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
            // a filtered sample between the two still sees the surface's radiance. Light leaving sideways goes to
            // every voxel of the column the surface makes opaque: each blocks a sideways cone by the surface's
            // opacity, so each must send the surface's light too (the resolve weighs the radiance by that opacity).
            // Kept in the samples' own voxels, the tilted plane's spread and the thickness were dark and opaque,
            // and a tilted wall sent a cone 70 % of its light (a closed sphere's cones gathered 63 %). Isotropic
            // emittance keeps each sample's light in its own voxel: its mips add light along the axes a surface
            // does not block, so light in the thickness too would count a wall twice.
            // The column's ends come from the geometry alone (not from what this update may write), so that a
            // voxel gets the same light whichever update writes it.
            bool axial = directions > 1u && d % 3u == uint(axis);
            int end = d < 3u ? k1 - k0 : 0;
            int behind = d < 3u ? end - 1 : end + 1;
            for (int k = 0; k < BL_VOXEL_MAX_SPAN; ++k) {
                uint count = axial ? ((k == end || (k == behind && behind <= k1 - k0)) ? inside : 0u)
                                   : (directions == 1u ? (samples >> (5u * uint(k))) & 31u : inside);
                if (count == 0u || (writable & (1u << uint(k))) == 0u) continue;
                ivec3 voxel = origin + blVoxelUnproject(ivec3(pixelInLevel, k0 + k), axis);
                precise float share = weight * float(count) * sampleArea;  // of the voxel's face, projected along d
                precise vec3 amount = radiance * (share * blVctFrame.scales.y);
                uvec4 units = uvec4(min(vec4(amount, share * VCT_COVERAGE_UNITS) + 0.5, vec4(4.0e9)));
                if (units == uvec4(0u)) continue;
                blVoxelAddLight(vctTexel(1u + d, level, voxel, resolution), units);
                ++emittanceWrites;
            }
        }
    }
    blVoxelCount(BL_VCT_COUNT_EMITTANCE_WRITES, emittanceWrites);
#endif
}

#ifndef BL_VOXEL_COMPUTE
void main() {
    blVoxelCount(BL_VCT_COUNT_FRAGMENTS, 1u);
    BlVoxelTriangle t;
    t.edge[0] = blVoxelEdge0;
    t.edge[1] = blVoxelEdge1;
    t.edge[2] = blVoxelEdge2;
    t.plane = blVoxelPlane;
    t.bounds = blVoxelBounds;
    t.depth = blVoxelDepth;
    t.levelAxis = blVoxelLevelAxis;
    t.faceNormal = blVoxelFaceNormal;
    t.offset = blVoxelOffset;
    t.opposite = vec3(1.0);  // unused per pixel
    BlVoxelUserGradient gradient = BlVoxelUserGradient(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
#ifdef BL_VOXEL_COVERAGE
    // Here, in uniform control flow. The attributes are linear over the quad (the geometry stage extrapolates them
    // over the triangle's plane, w = 1), so the differences between neighbouring pixels are their exact gradient.
    // Window x, y are the projection's u, v (the pixel is floor(gl_FragCoord.xy)).
    gradient = BlVoxelUserGradient(dFdx(blVoxelUser0Gs), dFdy(blVoxelUser0Gs), dFdx(blVoxelUser1Gs), dFdy(blVoxelUser1Gs));
#endif
    blVoxelPixel(t, ivec2(floor(gl_FragCoord.xy)), blVoxelNormalGs, blVoxelUser0Gs, blVoxelUser1Gs, gradient);
}
#endif

#endif  // BL_VOXEL_SETUP_ONLY
#endif
