#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// One group per allocated brick, one thread per brixel: the exact distance from the brixel's lattice
// point to the voxel's referenced triangles (every triangle within the band of the voxel), saturated at
// the band and stored as distance / band in the R8 atlas. Also the brick's tight AABB (brixels within one
// interval of a surface, grown by one); a brick with no brixel inside the band is freed (voxel EMPTY).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 8) in;
#define CHUNK 128u
BL_READ_BUFFER(0) Triangles { vec4 triangles[]; };
BL_READ_BUFFER(1) SortedReferences { uint sortedReferences[]; };
BL_READ_BUFFER(2) Touched { uvec4 touched[]; };
BL_READ_BUFFER(3) CascadeTable { BL_SDF_CASCADE_TABLE_BODY } table;
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) BrickAabbs { uint brickAabbs[]; };
BL_STORAGE_BUFFER(2) FreeStack { uint freeStack[]; };
BL_STORAGE_BUFFER(3) Counters { uint counters[]; };
BL_IMAGE(0, r8) uniform writeonly image3D atlas;

shared vec4 chunk[3u * CHUNK];
shared uint boxMin[3], boxMax[3], keep;

void main() {
    uint t = gl_WorkGroupID.y * BL_SDF_WIDE_GROUPS + gl_WorkGroupID.x;
    if (t >= counters[C_TOUCHED_COUNT]) return;  // uniform per group
    uvec4 entry = touched[t];
    if (entry.w == BL_SDF_UNBUILT) return;
    uint lane = gl_LocalInvocationIndex;
    if (lane < 3u) {
        boxMin[lane] = 7u;
        boxMax[lane] = 0u;
    }
    if (lane == 0u) keep = 0u;

    uint cascade = entry.x >> 24;
    uint physical = entry.x & 0xFFFFFFu;
    ivec3 origin = table.cascades[cascade].origin.xyz;
    ivec3 slot = ivec3(physical % 64u, (physical / 64u) % 64u, physical / 4096u);
    ivec3 voxel = origin + ((slot - origin) & ivec3(BL_SDF_CASCADE_RES - 1));
    float vs = table.cascades[cascade].voxelSize.x;
    float band = table.cascades[cascade].voxelSize.w;
    ivec3 b = ivec3(gl_LocalInvocationID);
    vec3 p = (vec3(voxel) + vec3(b) / 7.0) * vs;

    float best = band * band;
    for (uint base = 0u; base < entry.y; base += CHUNK) {
        uint n = min(CHUNK, entry.y - base);
        barrier();
        if (lane < n) {
            uint tri = sortedReferences[entry.z + base + lane];
            chunk[3u * lane] = triangles[3u * tri];
            chunk[3u * lane + 1u] = triangles[3u * tri + 1u];
            chunk[3u * lane + 2u] = triangles[3u * tri + 2u];
        }
        barrier();
        for (uint j = 0u; j < n; ++j) {
            vec3 a = chunk[3u * j].xyz, bb = chunk[3u * j + 1u].xyz, c = chunk[3u * j + 2u].xyz;
            // Cheap reject: the triangle's box is already farther than the best distance.
            vec3 outside = max(max(min(a, min(bb, c)) - p, p - max(a, max(bb, c))), vec3(0.0));
            if (dot(outside, outside) >= best) continue;
            best = min(best, blPointTriangleDistanceSq(p, a, bb, c));
        }
    }
    float d = sqrt(best);
    uint q = uint(floor(min(d, band) / band * 255.0 + 0.5));
    uint brick = entry.w;
    imageStore(atlas, blSdfBrickTexel(brick, table.header.y) + b, vec4(float(q) / 255.0));
    if (q < 255u) atomicOr(keep, 1u);
    if (d <= vs / 7.0) {
        for (int axis = 0; axis < 3; ++axis) {
            atomicMin(boxMin[axis], uint(b[axis]));
            atomicMax(boxMax[axis], uint(b[axis]));
        }
    }
    barrier();
    if (lane != 0u) return;
    uint key = cascade * BL_SDF_CASCADE_VOXELS + physical;
    if (keep == 0u) {
        brickMaps[key] = BL_SDF_EMPTY;
        brickAabbs[brick] = BL_SDF_AABB_NONE;
        uint top = atomicAdd(counters[C_FREE_COUNT], 1u);
        freeStack[top] = brick;
        atomicAdd(counters[C_BRICKS_FREED], 1u);
    } else if (boxMin[0] > boxMax[0]) {
        brickAabbs[brick] = BL_SDF_AABB_NONE;  // distances only: no surface inside the voxel
    } else {
        uvec3 lo = uvec3(max(ivec3(boxMin[0], boxMin[1], boxMin[2]) - 1, ivec3(0)));
        uvec3 hi = uvec3(min(ivec3(boxMax[0], boxMax[1], boxMax[2]) + 1, ivec3(7)));
        brickAabbs[brick] = lo.x | (lo.y << 3) | (lo.z << 6) | (hi.x << 9) | (hi.y << 12) | (hi.z << 15);
    }
    atomicAdd(counters[C_VOXELS_BUILT], 1u);
}
