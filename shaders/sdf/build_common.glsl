// Internal to the builder passes: counter indices, job table, triangle scratch and the exact
// point-triangle distance. Mirrors core/sdf/sdf_layout.h.
#ifndef BRICKLIGHT_SDF_BUILD_COMMON_GLSL
#define BRICKLIGHT_SDF_BUILD_COMMON_GLSL

#include "bricklight/sdf_layout.glsl"

// Counters buffer (uint). FREE_COUNT persists; the rest are cleared at the start of every update.
#define C_FREE_COUNT 0
#define C_ALLOC_CURSOR 1
#define C_REF_CURSOR 2
#define C_TOUCHED_COUNT 3
#define C_SORTED_CURSOR 4
#define C_BRICKS_ALLOCATED 5
#define C_BRICKS_FREED 6
#define C_TRIANGLES_REJECTED 7
#define C_VOXELS_DEFERRED 8
#define C_VOXELS_BUILT 9
#define C_TRIANGLES_PROCESSED 10
#define C_REFS_STORED 11
#define C_FREE_AT_ALLOCATION 12
#define C_REFS_IN_UPDATE 13
#define C_SPLIT_CURSOR 14        // bricks split over several groups (may pass BL_SDF_MAX_SPLIT_BRICKS: not split then)
#define C_SPLIT_WORK_CURSOR 15   // their chunks
#define C_BRICKS_SPLIT 16        // stats: bricks split, over the update's rounds

// Indirect argument slots (3 uints each) in the args buffer.
#define ARGS_PER_TOUCHED_64 0   // one thread per touched voxel, 64 per group
#define ARGS_PER_TOUCHED_BRICK 3 // one group per touched voxel (2D: x < 32768)
#define ARGS_PER_REFERENCE_64 6  // one thread per stored reference
#define ARGS_PER_SPLIT_BRICK 9   // one group per split brick (finalize)
#define BL_SDF_WIDE_GROUPS 32768u

// Job table: per-cascade bounds of this update's jobs, then the jobs.
//   cascadeBounds[2c] = min world voxel (w: 1 if the cascade has jobs), [2c+1] = max (exclusive)
//   jobs[2j] = min world voxel (xyz), cascade (w); jobs[2j+1] = size (xyz), first voxel of the job in
//   this update's job-voxel numbering (w)
#define BL_SDF_JOB_TABLE_BODY ivec4 cascadeBounds[2 * BL_SDF_MAX_CASCADES]; ivec4 jobs[];

// Touched voxel entries (uvec4): x = cascade << 24 | physical voxel, y = reference count (| BL_SDF_SPLIT_FLAG
// when its references are split over several groups), z = first sorted reference, w = brick (or
// BL_SDF_UNBUILT when none was allocated).
#define BL_SDF_SPLIT_FLAG 0x80000000u
#define BL_SDF_NO_SPLIT 0xFFFFFFFFu
// A brick with more references than this is split into chunks of this many, one group each.
#define BL_SDF_REFS_PER_GROUP 2048u
#define BL_SDF_MAX_SPLIT_BRICKS 2048u
#define BL_SDF_SPLIT_MINIMUM_CLEAR 0x7F800000u  // +inf: the split minima between rounds

// Triangle scratch: 3 vec4 per triangle, world space; v0.w = max cascade, or -1 for a rejected triangle;
// v1.w = 1 for an alpha-tested instance's triangle; v2.w = the instance's material tag: 1 + its index in the
// update's material table (two vec4 per instance: albedo, emission), 0 for an instance without a material.

float blDot2(vec3 v) { return dot(v, v); }

// Exact squared distance from p to triangle (a, b, c); degenerate triangles (segments, points) included.
float blPointTriangleDistanceSq(vec3 p, vec3 a, vec3 b, vec3 c) {
    vec3 ab = b - a, ac = c - a, ap = p - a;
    vec3 n = cross(ab, ac);
    float nn = dot(n, n);
    // Inside the prism over the triangle: the plane distance.
    if (nn > 1e-30) {
        float s0 = dot(cross(ab, ap), n);
        float s1 = dot(cross(c - b, p - b), n);
        float s2 = dot(cross(a - c, p - c), n);
        if (s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0) {
            float d = dot(n, ap);
            return d * d / nn;
        }
    }
    // Otherwise the nearest of the three edges.
    vec3 bc = c - b;
    float t0 = clamp(dot(ap, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
    float t1 = clamp(dot(p - b, bc) / max(dot(bc, bc), 1e-30), 0.0, 1.0);
    vec3 ca = a - c;
    float t2 = clamp(dot(p - c, ca) / max(dot(ca, ca), 1e-30), 0.0, 1.0);
    return min(blDot2(ap - ab * t0), min(blDot2(p - b - bc * t1), blDot2(p - c - ca * t2)));
}

#endif
