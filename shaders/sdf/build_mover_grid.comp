#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
#include "mover_grid.glsl"
// One thread per (triangle, level) of a mesh's mover grid (mover_grid.glsl): every lattice point within the
// reach of the triangle keeps the smaller of its key and the triangle's (distance quantized over the reach in
// the high bits, so the atomic minimum picks the nearest triangle; ties within a step of 1/4096 of the reach
// pick either, which the brick pass's exact evaluation of the candidates makes harmless). The keys start as
// BL_SDF_MOVER_NO_KEY (cleared by the caller); the triangles were gathered in object space before.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params {
    uint triangleCount;
    uint firstTriangle;  // vec4 index / 3 in moverGridData
    uint firstLevelRow;  // in moverGridTable
    uint pad;
} params;
BL_READ_BUFFER(0) MoverGridTable { uvec4 moverGridTable[]; };
BL_STORAGE_BUFFER(0) MoverGridData { uint moverGridData[]; };

vec3 vertexAt(uint word) { return uintBitsToFloat(uvec3(moverGridData[word], moverGridData[word + 1u], moverGridData[word + 2u])); }

void main() {
    uint tri = gl_GlobalInvocationID.y * (BL_SDF_WIDE_GROUPS * 64u) + gl_GlobalInvocationID.x;
    if (tri >= params.triangleCount) return;
    uint at = 12u * (params.firstTriangle + tri);
    if (uintBitsToFloat(moverGridData[at + 3u]) < 0.0) return;  // rejected by gather
    vec3 a = vertexAt(at), b = vertexAt(at + 4u), c = vertexAt(at + 8u);
    uint level = gl_WorkGroupID.z;
    uvec4 l0 = moverGridTable[params.firstLevelRow + 2u * level], l1 = moverGridTable[params.firstLevelRow + 2u * level + 1u];
    vec3 origin = uintBitsToFloat(l0.xyz);
    float inv = uintBitsToFloat(l0.w), spacing = 1.0 / inv;
    ivec3 dims = ivec3(l1.xyz);
    float reach = BL_SDF_MOVER_REACH_CELLS * spacing;
    ivec3 i0 = clamp(ivec3(ceil((min(a, min(b, c)) - origin) * inv - BL_SDF_MOVER_REACH_CELLS)), ivec3(0), dims - 1);
    ivec3 i1 = clamp(ivec3(floor((max(a, max(b, c)) - origin) * inv + BL_SDF_MOVER_REACH_CELLS)), ivec3(0), dims - 1);
    vec3 centre = (a + b + c) / 3.0;
    float sphere = sqrt(max(blDot2(a - centre), max(blDot2(b - centre), blDot2(c - centre)))) + reach;
    for (int z = i0.z; z <= i1.z; ++z)
        for (int y = i0.y; y <= i1.y; ++y)
            for (int x = i0.x; x <= i1.x; ++x) {
                vec3 p = origin + vec3(x, y, z) * spacing;
                if (blDot2(p - centre) > sphere * sphere) continue;
                float d2 = blPointTriangleDistanceSq(p, a, b, c);
                if (d2 > reach * reach) continue;
                uint step = min(uint(sqrt(d2) / reach * 4095.0), 4095u);
                uint key = (step << BL_SDF_MOVER_TRIANGLE_BITS) | tri;
                uint index = l1.w + uint((z * dims.y + y) * dims.x + x);
                if (key < moverGridData[index]) atomicMin(moverGridData[index], key);
            }
}
