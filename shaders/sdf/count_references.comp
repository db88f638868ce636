#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// One thread per gathered triangle: for every cascade the triangle goes into, every BUILDING voxel within
// the distance band of the triangle gets a reference (voxel, triangle, index within the voxel). The loop
// runs over the columns of the triangle's dominant plane with a depth range per column (cost ~ area).
// A mover grid's reference chunk (mover_grid.glsl) references the BUILDING voxels of its box in its cascade that
// the mover's surface may reach within the band.
// When the reference budget runs out the voxel is put back to UNBUILT (deferred, retried later).
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint triangleCount; uint cascadeCount; uint maxReferences; uint touchedCapacity; } params;
BL_READ_BUFFER(0) Triangles { vec4 triangles[]; };
BL_READ_BUFFER(1) CascadeTable { BL_SDF_CASCADE_TABLE_BODY } table;
BL_READ_BUFFER(2) JobTable { BL_SDF_JOB_TABLE_BODY } jobTable;
BL_STORAGE_BUFFER(0) BrickMaps { uint brickMaps[]; };
BL_STORAGE_BUFFER(1) VoxelRefs { uint voxelRefs[]; };
BL_STORAGE_BUFFER(2) References { uint references[]; };  // 3 per reference: key, triangle, index in voxel
BL_STORAGE_BUFFER(3) Touched { uvec4 touched[]; };
BL_STORAGE_BUFFER(4) Counters { uint counters[]; };
BL_STORAGE_BUFFER(5) MoverGridTable { uvec4 moverGridTable[]; };  // read only
BL_STORAGE_BUFFER(6) MoverGridData { uint moverGridData[]; };      // read only
#define BL_SDF_MOVER_SAMPLING
#include "mover_grid.glsl"

shared uint groupProcessed;

void emitReference(uint cascade, ivec3 voxel, uint tri) {
    uint key = cascade * BL_SDF_CASCADE_VOXELS + blSdfPhysicalIndex(voxel);
    if (brickMaps[key] != BL_SDF_BUILDING) return;
    uint r = atomicAdd(counters[C_REF_CURSOR], 1u);
    if (r >= params.maxReferences) {
        if (atomicCompSwap(brickMaps[key], BL_SDF_BUILDING, BL_SDF_UNBUILT) == BL_SDF_BUILDING)
            atomicAdd(counters[C_VOXELS_DEFERRED], 1u);
        return;
    }
    uint local = atomicAdd(voxelRefs[2u * key], 1u);
    if (local == 0u) {
        uint t = atomicAdd(counters[C_TOUCHED_COUNT], 1u);
        voxelRefs[2u * key + 1u] = t;
        touched[t] = uvec4((cascade << 24) | blSdfPhysicalIndex(voxel), 0u, 0u, BL_SDF_UNBUILT);
    }
    references[3u * r] = key;
    references[3u * r + 1u] = tri;
    references[3u * r + 2u] = local;
}

void main() {
    if (gl_LocalInvocationIndex == 0u) groupProcessed = 0u;
    barrier();
    uint tri = gl_GlobalInvocationID.y * (BL_SDF_WIDE_GROUPS * 64u) + gl_GlobalInvocationID.x;
    vec4 v0 = tri < params.triangleCount ? triangles[3u * tri] : vec4(0.0, 0.0, 0.0, -1.0);
    vec4 v1 = tri < params.triangleCount ? triangles[3u * tri + 1u] : vec4(0.0);
    if (v0.w >= 0.0 && v1.w > BL_SDF_MOVER_TAG - 0.5) {
        uint cascade = uint(v0.w);
        ivec4 bmin = jobTable.cascadeBounds[2u * cascade];
        ivec4 bmax = jobTable.cascadeBounds[2u * cascade + 1u];
        ivec3 lo = max(ivec3(v0.xyz), bmin.xyz), hi = min(ivec3(v1.xyz), bmax.xyz - 1);
        // Voxels of the chunk whose centre is farther from the mesh than the band plus the voxel's half diagonal
        // have no sample within the band: not referenced (most of a footprint box, around a compact mesh).
        uint m = uint(v1.w - BL_SDF_MOVER_TAG + 0.5);
        float vs = table.cascades[cascade].voxelSize.x;
        float needed = table.cascades[cascade].voxelSize.w + 0.8660254 * vs;
        if (bmin.w != 0)
            for (int z = lo.z; z <= hi.z; ++z)
                for (int y = lo.y; y <= hi.y; ++y)
                    for (int x = lo.x; x <= hi.x; ++x)
                        if (blSdfMoverLowerBound(m, cascade, (vec3(x, y, z) + 0.5) * vs) < needed)
                            emitReference(cascade, ivec3(x, y, z), tri);
    } else if (v0.w >= 0.0) {
        atomicAdd(groupProcessed, 1u);
        vec3 a = v0.xyz, b = v1.xyz, c = triangles[3u * tri + 2u].xyz;
        vec3 n = cross(b - a, c - a);
        float nLength = length(n);
        uint lastCascade = min(uint(v0.w), params.cascadeCount - 1u);
        for (uint cascade = 0u; cascade <= lastCascade; ++cascade) {
            ivec4 bmin = jobTable.cascadeBounds[2u * cascade];
            ivec4 bmax = jobTable.cascadeBounds[2u * cascade + 1u];
            if (bmin.w == 0) continue;
            float vs = table.cascades[cascade].voxelSize.x, inv = table.cascades[cascade].voxelSize.y;
            float band = table.cascades[cascade].voxelSize.w;
            ivec3 lo = max(ivec3(floor((min(a, min(b, c)) - band) * inv)), bmin.xyz);
            ivec3 hi = min(ivec3(floor((max(a, max(b, c)) + band) * inv)), bmax.xyz - 1);
            if (any(greaterThan(lo, hi))) continue;
            if (nLength < 1e-12 * max(1.0, vs * vs)) {
                // Degenerate (a segment or a point): its small box is the conservative footprint.
                for (int z = lo.z; z <= hi.z; ++z)
                    for (int y = lo.y; y <= hi.y; ++y)
                        for (int x = lo.x; x <= hi.x; ++x) emitReference(cascade, ivec3(x, y, z), tri);
                continue;
            }
            vec3 nn = n / nLength;
            vec3 an = abs(nn);
            int k = (an.x >= an.y && an.x >= an.z) ? 0 : (an.y >= an.z ? 1 : 2);
            int u = (k + 1) % 3, w = (k + 2) % 3;
            float d0 = dot(nn, a);
            float reach = band / an[k];
            for (int iw = lo[w]; iw <= hi[w]; ++iw) {
                for (int iu = lo[u]; iu <= hi[u]; ++iu) {
                    // Plane height along k at the four corners of the column, widened by the band.
                    float kMin = 1e30, kMax = -1e30;
                    for (int corner = 0; corner < 4; ++corner) {
                        float xu = float(iu + (corner & 1)) * vs, xw = float(iw + (corner >> 1)) * vs;
                        float xk = (d0 - nn[u] * xu - nn[w] * xw) / nn[k];
                        kMin = min(kMin, xk);
                        kMax = max(kMax, xk);
                    }
                    int k0 = max(lo[k], int(floor((kMin - reach) * inv)));
                    int k1 = min(hi[k], int(floor((kMax + reach) * inv)));
                    for (int ik = k0; ik <= k1; ++ik) {
                        ivec3 voxel;
                        voxel[k] = ik;
                        voxel[u] = iu;
                        voxel[w] = iw;
                        emitReference(cascade, voxel, tri);
                    }
                }
            }
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && groupProcessed > 0u) atomicAdd(counters[C_TRIANGLES_PROCESSED], groupProcessed);
}
