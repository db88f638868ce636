#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"
// Voxelization, geometry stage (vct::Clipmap::voxelizationState): one invocation per clip-map level projects the
// triangle along its dominant axis into that level's voxel grid. Every level has the same resolution, so one
// resolution² viewport serves all of them: the level is a flat output, not a viewport index.
//
// Neither lavapipe nor llvmpipe has conservative rasterization, and we want no triangle lost however small:
// the triangle's 2D bounding box, grown by half a pixel, is emitted as a quad, and the fragment shader decides
// per pixel with the triangle's exact edge functions (bricklight/voxelize.glsl). The application's attributes
// are extrapolated linearly over the triangle's plane to the quad's corners.
layout(triangles, invocations = 8) in;
layout(triangle_strip, max_vertices = 4) out;

BL_VCT_FRAME_BLOCK(7);
BL_CONSTANTS(3) uniform BlVoxelMaterial {
    vec4 material;  // x thickness in voxels of the level, y opacity (0..1), z two-sided (0 or 1)
} blVoxelMaterial;

layout(location = 0) in vec3 blVoxelNormalIn[];
layout(location = 1) in vec4 blVoxelUser0In[];
layout(location = 2) in vec4 blVoxelUser1In[];

layout(location = 0) out vec3 blVoxelNormalGs;
layout(location = 1) out vec4 blVoxelUser0Gs;
layout(location = 2) out vec4 blVoxelUser1Gs;
layout(location = 3) flat out vec4 blVoxelEdge0;   // edges: xy unit inward normal n, zw a point p; n·(x − p) ≥ 0 inside
layout(location = 4) flat out vec4 blVoxelEdge1;
layout(location = 5) flat out vec4 blVoxelEdge2;
layout(location = 6) flat out vec4 blVoxelPlane;   // depth w = x + y·u + z·v; w: surface area per projected area
layout(location = 7) flat out vec4 blVoxelBounds;  // the triangle's (u, v) bounding box: min xy, max zw
// (Edges, plane, bounds and depth range are in the triangle's frame, blVoxelOffset voxels from the level's origin.)
layout(location = 8) flat out vec4 blVoxelDepth;   // x, y: the triangle's depth range; z thickness; w opacity
layout(location = 9) flat out ivec4 blVoxelLevelAxis;  // x level, y projection axis, z two-sided
layout(location = 10) flat out vec3 blVoxelFaceNormal; // unit geometric normal in world space (winding order)
layout(location = 11) flat out ivec3 blVoxelOffset;    // the triangle's frame in the level, projected (u, v, w)

// (u, v, w): the two projected coordinates and the depth along `axis`.
vec3 project(vec3 p, int axis) { return axis == 0 ? p.yzx : (axis == 1 ? p.zxy : p); }

void main() {
    uint level = uint(gl_InvocationID);
    if (level >= blVctFrame.params.y) return;
    float resolution = float(blVctFrame.params.x);
    float voxelSize = blVctFrame.scales.x * float(1u << level);
    // The triangle in its own frame: voxel units relative to the voxel of its first vertex. Everything the
    // fragment shader tests is computed there, so that a triangle gives bit-identical results wherever the level
    // lies (a scrolled clip-map equals one voxelized from scratch); `offset` (integer) places that frame in the
    // level.
    vec3 pv[3];
    for (int i = 0; i < 3; ++i) pv[i] = gl_in[i].gl_Position.xyz / voxelSize;
    // Non-finite or absurdly distant vertices would make every edge test meaningless: drop the triangle.
    for (int i = 0; i < 3; ++i)
        if (any(isnan(pv[i])) || any(greaterThan(abs(pv[i]), vec3(1.0e8)))) return;
    vec3 base = floor(pv[0]);
    ivec3 offset = ivec3(base) - blVctFrame.origin[level].xyz;
    vec3 p[3];
    for (int i = 0; i < 3; ++i) p[i] = pv[i] - base;
    if (any(greaterThan(abs(p[1]), vec3(1.0e7))) || any(greaterThan(abs(p[2]), vec3(1.0e7)))) return;

    float thickness = clamp(blVoxelMaterial.material.x, 0.0, 2.0);
    float pad = 1.0 + 0.5 * thickness;
    vec3 lo = min(min(p[0], p[1]), p[2]) + vec3(offset), hi = max(max(p[0], p[1]), p[2]) + vec3(offset);
    if (any(greaterThan(lo, vec3(resolution + pad))) || any(lessThan(hi, vec3(-pad)))) return;
    if (level > 0u) {
        // Wholly inside the finer level: those voxels come from downsampling it.
        vec3 finerLo = vec3(blVctFrame.origin[level - 1u].xyz) * 0.5 - vec3(blVctFrame.origin[level].xyz);
        vec3 finerHi = finerLo + 0.5 * resolution;
        if (all(greaterThanEqual(lo - pad, finerLo)) && all(lessThanEqual(hi + pad, finerHi))) return;
    }

    // precise: no fused multiply-adds, so that Vulkan and GL round alike (the emittance words must agree).
    precise vec3 n = cross(p[1] - p[0], p[2] - p[0]);
    vec3 an = abs(n);
    int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    vec3 q[3];
    for (int i = 0; i < 3; ++i) q[i] = project(p[i], axis);
    vec3 nq = project(n, axis);
    if (nq.z == 0.0) return;  // degenerate: no area at float precision
    float orientation = nq.z > 0.0 ? 1.0 : -1.0;  // counter-clockwise in (u, v) when positive

    // Each edge is anchored at its lexicographically smaller end, so that the two triangles sharing an edge
    // compute exactly opposite values at any point (the fragment shader's fill rule relies on it).
    vec4 edges[3];
    for (int i = 0; i < 3; ++i) {
        vec2 a = q[i].xy, b = q[(i + 1) % 3].xy;
        vec2 e = orientation * vec2(a.y - b.y, b.x - a.x);
        e /= length(e);
        edges[i] = vec4(e, a.x < b.x || (a.x == b.x && a.y < b.y) ? a : b);
    }
    precise vec4 plane = vec4(q[0].z + (nq.x * q[0].x + nq.y * q[0].y) / nq.z, -nq.x / nq.z, -nq.y / nq.z,
                      length(n) / abs(nq.z));
    vec2 uvLo = min(min(q[0].xy, q[1].xy), q[2].xy), uvHi = max(max(q[0].xy, q[1].xy), q[2].xy);
    vec2 depthRange = vec2(min(min(q[0].z, q[1].z), q[2].z), max(max(q[0].z, q[1].z), q[2].z));
    // Barycentric weights of a point: edge i is opposite vertex (i + 2) % 3.
    float opposite[3];
    for (int i = 0; i < 3; ++i) opposite[(i + 2) % 3] = dot(edges[i].xy, q[(i + 2) % 3].xy - edges[i].zw);

    // Every pixel whose square touches the bounding box has its centre inside the quad (with a margin, so that
    // the rasterizer's rules at edges never matter).
    const float grow = 0.5 + 1.0 / 64.0;
    vec2 corners[4] = vec2[4](vec2(uvLo.x - grow, uvLo.y - grow), vec2(uvHi.x + grow, uvLo.y - grow),
                              vec2(uvLo.x - grow, uvHi.y + grow), vec2(uvHi.x + grow, uvHi.y + grow));
    for (int c = 0; c < 4; ++c) {
        vec3 weight;
        for (int i = 0; i < 3; ++i) weight[(i + 2) % 3] = dot(edges[i].xy, corners[c] - edges[i].zw) / opposite[(i + 2) % 3];
        blVoxelNormalGs = weight.x * blVoxelNormalIn[0] + weight.y * blVoxelNormalIn[1] + weight.z * blVoxelNormalIn[2];
        blVoxelUser0Gs = weight.x * blVoxelUser0In[0] + weight.y * blVoxelUser0In[1] + weight.z * blVoxelUser0In[2];
        blVoxelUser1Gs = weight.x * blVoxelUser1In[0] + weight.y * blVoxelUser1In[1] + weight.z * blVoxelUser1In[2];
        blVoxelEdge0 = edges[0];
        blVoxelEdge1 = edges[1];
        blVoxelEdge2 = edges[2];
        blVoxelPlane = plane;
        blVoxelBounds = vec4(uvLo, uvHi);
        blVoxelDepth = vec4(depthRange, thickness, clamp(blVoxelMaterial.material.y, 0.0, 1.0));
        blVoxelLevelAxis = ivec4(int(level), axis, blVoxelMaterial.material.z != 0.0 ? 1 : 0, 0);
        precise vec3 unitNormal = n / length(n);
        blVoxelFaceNormal = unitNormal;
        blVoxelOffset = ivec3(project(vec3(offset), axis));
        gl_Position = vec4((corners[c] + vec2(blVoxelOffset.xy)) / resolution * 2.0 - 1.0, 0.5, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
