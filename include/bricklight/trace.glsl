// Bricklight public trace API: rays against the sparse brick distance field of an sdf::SdfScene.
//
//   #include "bricklight/trace.glsl"
//   ...
//   BlSdfRay ray = blSdfMakeRay(origin, direction, 0.0, 1e30);
//   BlSdfHit hit = blSdfTrace(ray);
//   if (hit.hit) { ... hit.t, hit.normal, hit.cascade ... }
//
// The caller's record merges SdfScene::traceBindings(): one sampled texture (BL_SDF_ATLAS_SLOT, default 15)
// and four read buffers starting at BL_SDF_READ_BUFFER_BASE (default 4). Define either before the include
// to move them (and pass the same TraceSlots to traceBindings).
//
// A ray walks its cascades from startCascade to endCascade. It uses a cascade only while its cursor is
// inside it; when it leaves a cascade, meets a voxel not built yet, or runs out of iterations there, it
// continues in the next coarser one from where it got to. Within a cascade it descends the 3-level AABB
// tree (mid nodes of 16³ voxels, bottom nodes of 4³, per-brick boxes) and sphere-traces inside bricks.
#ifndef BRICKLIGHT_TRACE_GLSL
#define BRICKLIGHT_TRACE_GLSL

#include "bricklight/bindings.glsl"
#include "bricklight/sdf_layout.glsl"

#ifndef BL_SDF_ATLAS_SLOT
#define BL_SDF_ATLAS_SLOT 15
#endif
#ifndef BL_SDF_READ_BUFFER_BASE
#define BL_SDF_READ_BUFFER_BASE 4
#endif
// Node, voxel and sphere-tracing steps allowed per cascade before the ray moves to the next cascade: the
// default of BlSdfRay::maxIterations.
#ifndef BL_SDF_MAX_ITERATIONS
#define BL_SDF_MAX_ITERATIONS 384u
#endif

BL_TEXTURE(BL_SDF_ATLAS_SLOT) uniform sampler3D blSdfAtlas;
BL_READ_BUFFER(BL_SDF_READ_BUFFER_BASE + 0) BlSdfCascadeTable { BL_SDF_CASCADE_TABLE_BODY } blSdfTable;
BL_READ_BUFFER(BL_SDF_READ_BUFFER_BASE + 1) BlSdfBrickMaps { uint blSdfBrickMaps[]; };
BL_READ_BUFFER(BL_SDF_READ_BUFFER_BASE + 2) BlSdfTrees { uint blSdfTrees[]; };
BL_READ_BUFFER(BL_SDF_READ_BUFFER_BASE + 3) BlSdfBrickAabbs { uint blSdfBrickAabbs[]; };

struct BlSdfRay {
    vec3 origin;
    vec3 direction;  // normalised
    float tMin;
    float tMax;
    uint startCascade;
    uint endCascade;  // inclusive; clamped to the scene's cascades
    float epsilonScale;  // multiplies the cascades' hit epsilon (1 by default)
    // Node, voxel and sphere-tracing steps per cascade before the ray goes on in the next coarser one
    // (BL_SDF_MAX_ITERATIONS by default). A small budget bounds the cost of the slowest rays (those that
    // graze surfaces or walk long stretches of a fine cascade) at the price of coarser answers for them.
    uint maxIterations;
    // Cone-like tracing, for rays that stand for a cone (diffuse GI): once t passes this many voxels of the
    // current cascade, the ray goes on in the next coarser one, as the cone's footprint has outgrown the
    // voxel. 0 (the default): a ray leaves a cascade only at its boundary.
    float coarsenAfterVoxels;
};

struct BlSdfHit {
    bool hit;
    float t;           // world units along the ray (tMax on a miss)
    vec3 normal;       // unit, facing the ray
    uint brickId;
    vec3 brickUvw;     // position within the brick's voxel, [0,1]³
    uint cascade;
    uint iterations;   // nodes, voxels and sphere-tracing steps visited, over all cascades
    // No hit and no miss: the last cascade ran out of iterations (or met a voxel not built yet) before
    // tMax. Callers that treat a miss as "the sky" should not do so for these rays.
    bool gaveUp;
    // The surface hit may be a cut-out part of an alpha-tested instance (sdf::InstanceDesc::alphaTested): the
    // brick holds such surfaces and no opaque surface reaches this 4³ cell of it. A tracer that knows the
    // coverage there may go on past it (blSdfContinueRay); else the card is solid.
    bool alphaTested;
};

BlSdfRay blSdfMakeRay(vec3 origin, vec3 direction, float tMin, float tMax) {
    BlSdfRay r;
    r.origin = origin;
    r.direction = direction;
    r.tMin = tMin;
    r.tMax = tMax;
    r.startCascade = 0u;
    r.endCascade = BL_SDF_MAX_CASCADES - 1u;
    r.epsilonScale = 1.0;
    r.maxIterations = BL_SDF_MAX_ITERATIONS;
    r.coarsenAfterVoxels = 0.0;
    return r;
}

// Entry and exit of a ray (origin o, inverse direction inv) through the box [lo, hi].
vec2 blSdfRayBox(vec3 o, vec3 inv, vec3 lo, vec3 hi) {
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    return vec2(max(tn.x, max(tn.y, tn.z)), min(tf.x, min(tf.y, tf.z)));
}

// Distance (world units, saturated at the band) inside a brick at brick-local position uvw in [0,1]³.
float blSdfSampleBrick(uint brick, vec3 uvw) {
    uint perAxis = blSdfTable.header.y;
    vec3 texel = vec3(blSdfBrickTexel(brick, perAxis)) + 0.5 + clamp(uvw, 0.0, 1.0) * 7.0;
    return textureLod(blSdfAtlas, texel / float(perAxis * 8u), 0.0).r;  // in units of the band
}

vec3 blSdfBrickNormal(uint brick, vec3 uvw, vec3 direction) {
    const float h = 1.0 / 7.0;
    vec3 g = vec3(blSdfSampleBrick(brick, uvw + vec3(h, 0, 0)) - blSdfSampleBrick(brick, uvw - vec3(h, 0, 0)),
                  blSdfSampleBrick(brick, uvw + vec3(0, h, 0)) - blSdfSampleBrick(brick, uvw - vec3(0, h, 0)),
                  blSdfSampleBrick(brick, uvw + vec3(0, 0, h)) - blSdfSampleBrick(brick, uvw - vec3(0, 0, h)));
    float len = length(g);
    vec3 n = len > 1e-6 ? g / len : -direction;
    return dot(n, direction) > 0.0 ? -n : n;
}

// The 4³ cell of a brick that holds brick-local position uvw: (z·4 + y)·4 + x.
uint blSdfBrickCell(vec3 uvw) {
    uvec3 c = uvec3(clamp(ivec3(floor(uvw * 4.0)), ivec3(0), ivec3(3)));
    return (c.z * 4u + c.y) * 4u + c.x;
}

// Whether a hit at brick-local uvw in a brick flagged BL_SDF_AABB_ALPHA_TESTED may be a cut-out texel: no
// opaque surface reaches its cell.
bool blSdfCellAlphaTested(uint brick, vec3 uvw) {
    uint bit = blSdfBrickCell(uvw);
    uint opaque = blSdfBrickAabbs[blSdfTable.header.z + 2u * brick + (bit >> 5)];
    return (opaque & (1u << (bit & 31u))) == 0u;
}

// The surface material the field holds for a brick (sdf::InstanceDesc::material): x = albedo RGBA8 (alpha 255
// known, 0 none), y = emission RGB9E5 (bricklight/rgb9e5.glsl).
uvec2 blSdfBrickMaterial(uint brick) {
    uint at = blSdfTable.header.z * (1u + BL_SDF_OPAQUE_CELL_WORDS) + BL_SDF_MATERIAL_WORDS * brick;
    return uvec2(blSdfBrickAabbs[at], blSdfBrickAabbs[at + 1u]);
}

// A ray that goes on past a hit judged transparent (a cut-out texel of an alpha-tested card): it restarts
// beyond the hit, far enough along that the card's own thin shell of distances below the hit epsilon is
// behind it (2.5 epsilons off the surface, at most 3 brixel intervals along a grazing ray). Its tMin moves
// on; everything else is kept.
BlSdfRay blSdfContinueRay(BlSdfRay ray, BlSdfHit hit) {
    BlSdfCascade info = blSdfTable.cascades[hit.cascade];
    float eps = info.voxelSize.z * ray.epsilonScale;
    float cosine = max(abs(dot(hit.normal, ray.direction)), 1e-3);
    float along = min(2.5 * eps / cosine, 3.0 * info.voxelSize.x / 7.0);
    ray.tMin = hit.t + max(along, eps);
    return ray;
}

// Distance at a world position in one cascade: band (world) in empty voxels, -1 where nothing is built.
float blSdfDistance(vec3 position, uint cascade) {
    BlSdfCascade info = blSdfTable.cascades[cascade];
    vec3 local = position * info.voxelSize.y - vec3(info.origin.xyz);
    if (info.origin.w == 0 || any(lessThan(local, vec3(0.0))) || any(greaterThanEqual(local, vec3(64.0)))) return -1.0;
    ivec3 cell = ivec3(floor(local));
    uint state = blSdfBrickMaps[cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(info.origin.xyz + cell)];
    if (state == BL_SDF_EMPTY) return info.voxelSize.w;
    if (state >= BL_SDF_FIRST_STATE) return -1.0;
    return blSdfSampleBrick(state, local - vec3(cell)) * info.voxelSize.w;
}

BlSdfHit blSdfTrace(BlSdfRay ray) {
    BlSdfHit hit;
    hit.hit = false;
    hit.t = ray.tMax;
    hit.normal = vec3(0.0);
    hit.brickId = BL_SDF_UNBUILT;
    hit.brickUvw = vec3(0.0);
    hit.cascade = 0u;
    hit.iterations = 0u;
    hit.gaveUp = false;
    hit.alphaTested = false;
    float t = ray.tMin;
    uint lastCascade = min(ray.endCascade, blSdfTable.header.x - 1u);
    for (uint c = ray.startCascade; c <= lastCascade && t < ray.tMax; ++c) {
        BlSdfCascade info = blSdfTable.cascades[c];
        if (info.origin.w == 0) continue;
        float inv = info.voxelSize.y, eps = info.voxelSize.z * ray.epsilonScale, band = info.voxelSize.w;
        // Logical voxel space of this cascade; t stays in world units.
        vec3 o = ray.origin * inv - vec3(info.origin.xyz);
        vec3 d = ray.direction * inv;
        d = mix(d, vec3(1e-20), lessThan(abs(d), vec3(1e-20)));  // no zero components (no NaN below)
        vec3 invD = 1.0 / d;
        vec2 box = blSdfRayBox(o, invD, vec3(0.0), vec3(64.0));
        if (!(box.x <= t && t < box.y)) continue;  // the cursor is not inside this cascade
        float cascadeExit = min(box.y, ray.tMax);
        if (ray.coarsenAfterVoxels > 0.0 && c < lastCascade) cascadeExit = min(cascadeExit, ray.coarsenAfterVoxels * info.voxelSize.x);
        if (!(t < cascadeExit)) continue;
        uint treeBase = c * BL_SDF_TREE_STRIDE;
        vec3 rootMin = uintBitsToFloat(uvec3(blSdfTrees[treeBase + BL_SDF_TREE_ROOT], blSdfTrees[treeBase + BL_SDF_TREE_ROOT + 1u],
                                             blSdfTrees[treeBase + BL_SDF_TREE_ROOT + 2u]));
        vec3 rootMax = uintBitsToFloat(uvec3(blSdfTrees[treeBase + BL_SDF_TREE_ROOT + 4u], blSdfTrees[treeBase + BL_SDF_TREE_ROOT + 5u],
                                             blSdfTrees[treeBase + BL_SDF_TREE_ROOT + 6u]));
        vec2 root = blSdfRayBox(o, invD, rootMin, rootMax);
        float end = min(cascadeExit, root.y);
        float cursor = max(t, root.x);
        bool fallBack = false;  // unbuilt voxel or out of iterations: go on in the next cascade from `cursor`
        uint steps = 0u;
        float progress = 1e-4 * info.voxelSize.x;  // the smallest step, against getting stuck on a boundary
        vec3 nudge = sign(d) * 1e-4;
        while (cursor < end) {
            if (++steps > ray.maxIterations) {
                fallBack = true;
                break;
            }
            vec3 p = o + d * cursor;
            ivec3 cell = clamp(ivec3(floor(p + nudge)), ivec3(0), ivec3(63));
            ivec3 mid = cell >> 4, bottom = cell >> 2;
            // The three levels' words (mid node, bottom node, brick map) depend only on the cell: loaded
            // together, one memory round trip per step instead of one per level.
            uint midAt = treeBase + BL_SDF_TREE_MID + 8u * uint((mid.z * 4 + mid.y) * 4 + mid.x);
            uvec3 midLo = uvec3(blSdfTrees[midAt], blSdfTrees[midAt + 1u], blSdfTrees[midAt + 2u]);
            uvec3 midHi = uvec3(blSdfTrees[midAt + 4u], blSdfTrees[midAt + 5u], blSdfTrees[midAt + 6u]);
            uint bits = blSdfTrees[treeBase + uint((bottom.z * 16 + bottom.y) * 16 + bottom.x)];
            uint state = blSdfBrickMaps[c * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(info.origin.xyz + cell)];
            // Mid node (16³ voxels).
            vec2 span = blSdfRayBox(o, invD, uintBitsToFloat(midLo), uintBitsToFloat(midHi));
            if (span.x > span.y || span.y < cursor) {
                cursor = max(blSdfRayBox(o, invD, vec3(mid * 16), vec3(mid * 16 + 16)).y, cursor + progress);
                continue;
            }
            // Bottom node (4³ voxels).
            if (bits != BL_SDF_NODE_EMPTY) {
                vec3 nmin = vec3(uvec3(bits, bits >> 5, bits >> 10) & 31u) / 7.0;
                vec3 nmax = vec3(uvec3(bits >> 15, bits >> 20, bits >> 25) & 31u) / 7.0;
                span = blSdfRayBox(o, invD, vec3(bottom * 4) + nmin, vec3(bottom * 4) + nmax);
            }
            if (bits == BL_SDF_NODE_EMPTY || span.x > span.y || span.y < cursor) {
                cursor = max(blSdfRayBox(o, invD, vec3(bottom * 4), vec3(bottom * 4 + 4)).y, cursor + progress);
                continue;
            }
            // Voxel.
            float voxelExit = max(blSdfRayBox(o, invD, vec3(cell), vec3(cell + 1)).y, cursor + progress);
            if (state == BL_SDF_EMPTY) {
                cursor = voxelExit;
                continue;
            }
            if (state >= BL_SDF_FIRST_STATE) {
                fallBack = true;
                break;
            }
            uint aabb = blSdfBrickAabbs[state];
            if (aabb != BL_SDF_AABB_NONE) {
                span = blSdfRayBox(o, invD, vec3(cell) + vec3(blSdfAabbMin(aabb)) / 7.0, vec3(cell) + vec3(blSdfAabbMax(aabb)) / 7.0);
                float s = max(cursor, span.x), sEnd = min(span.y, min(voxelExit, end));
                // Sphere tracing; the smallest step is eps, so the voxel's diagonal (12.1 brixels) takes
                // at most ~21 steps of 0.6 brixel.
                while (s <= sEnd && steps <= ray.maxIterations) {
                    ++steps;
                    vec3 uvw = o + d * s - vec3(cell);
                    float dist = blSdfSampleBrick(state, uvw) * band;
                    if (dist < eps) {
                        hit.hit = true;
                        hit.t = s;
                        hit.brickId = state;
                        hit.brickUvw = clamp(uvw, 0.0, 1.0);
                        hit.cascade = c;
                        hit.normal = blSdfBrickNormal(state, hit.brickUvw, ray.direction);
                        hit.iterations += steps;
                        hit.alphaTested = (aabb & BL_SDF_AABB_ALPHA_TESTED) != 0u && blSdfCellAlphaTested(state, hit.brickUvw);
                        return hit;
                    }
                    s += dist;
                }
            }
            cursor = voxelExit;
        }
        hit.iterations += steps;
        t = fallBack ? cursor : cascadeExit;
        hit.gaveUp = fallBack;
    }
    return hit;
}

#endif
