#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "build_common.glsl"
// Fetches one instance's triangles from its vertex/index buffers (any stride and offset, f32x3 or f16x4
// positions, u16/u32 indices), transforms them to world space and appends them to the triangle scratch.
// Triangles with an index out of range, a non-finite position or a vertex outside the mesh's declared
// bounds are rejected: stored as disabled and counted.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params {
    vec4 rows[3];          // affine transform, row-major 3x4
    vec4 boundsMin;        // local bounds, xyz (w: tolerance)
    vec4 boundsMax;
    uvec4 vertex;          // x: byte offset, y: stride, z: format (0 f32x3, 1 f16x4), w: vertex count
    uvec4 index;           // x: byte offset, y: format (0 u16, 1 u32), z: triangle count, w: first output triangle
    uvec4 misc;            // x: max cascade, y: 1 for an alpha-tested instance, z: material tag (0: none)
} params;
BL_READ_BUFFER(0) Vertices { uint vertexWords[]; };
BL_READ_BUFFER(1) Indices { uint indexWords[]; };
BL_STORAGE_BUFFER(0) Triangles { vec4 triangles[]; };
BL_STORAGE_BUFFER(1) Counters { uint counters[]; };

uint loadIndex(uint i) {
    if (params.index.y == 1u) return indexWords[(params.index.x >> 2) + i];
    uint byteAddress = params.index.x + 2u * i;
    uint word = indexWords[byteAddress >> 2];
    return (byteAddress & 2u) != 0u ? (word >> 16) : (word & 0xFFFFu);
}

vec3 loadPosition(uint v) {
    uint word = (params.vertex.x + v * params.vertex.y) >> 2;
    if (params.vertex.z == 0u)
        return uintBitsToFloat(uvec3(vertexWords[word], vertexWords[word + 1u], vertexWords[word + 2u]));
    vec2 xy = unpackHalf2x16(vertexWords[word]);
    vec2 zw = unpackHalf2x16(vertexWords[word + 1u]);
    return vec3(xy, zw.x);
}

bool usable(vec3 p) {
    if (any(isnan(p)) || any(isinf(p))) return false;
    vec3 tolerance = vec3(params.boundsMin.w);
    return all(greaterThanEqual(p, params.boundsMin.xyz - tolerance)) && all(lessThanEqual(p, params.boundsMax.xyz + tolerance));
}

void main() {
    uint tri = gl_GlobalInvocationID.y * (BL_SDF_WIDE_GROUPS * 64u) + gl_GlobalInvocationID.x;
    if (tri >= params.index.z) return;
    uint i0 = loadIndex(3u * tri), i1 = loadIndex(3u * tri + 1u), i2 = loadIndex(3u * tri + 2u);
    bool ok = max(i0, max(i1, i2)) < params.vertex.w;
    vec3 p[3];
    p[0] = ok ? loadPosition(i0) : vec3(0.0);
    p[1] = ok ? loadPosition(i1) : vec3(0.0);
    p[2] = ok ? loadPosition(i2) : vec3(0.0);
    ok = ok && usable(p[0]) && usable(p[1]) && usable(p[2]);
    uint out0 = 3u * (params.index.w + tri);
    for (int k = 0; k < 3; ++k) {
        vec4 h = vec4(p[k], 1.0);
        vec3 w = vec3(dot(params.rows[0], h), dot(params.rows[1], h), dot(params.rows[2], h));
        float tag = k == 0 ? (ok ? float(params.misc.x) : -1.0) : (k == 1 ? float(params.misc.y) : float(params.misc.z));
        triangles[out0 + uint(k)] = vec4(w, tag);
    }
    if (!ok) atomicAdd(counters[C_TRIANGLES_REJECTED], 1u);
}
