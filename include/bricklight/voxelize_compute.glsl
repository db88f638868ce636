// The compute voxelizer of vct::VoxelScene's registered meshes (VoxelScene::setVoxelizer(Voxelizer::Compute)):
// one invocation per triangle and clip-map level does what the draw path's geometry stage and fragments do (bricklight/voxelize.glsl's blVoxelSetupTriangle, then blVoxelPixel for every pixel the triangle's
// bounding box touches). Triangles larger than VoxelScene's split limit are not voxelized here: their indices
// go to a list that VoxelScene then draws through the material's voxelization record, so that every triangle
// is voxelized exactly once per level.
//
// An application whose material has emittance writes, besides its voxelization fragment shader, a compute
// shader of the same three lines and sets it as VoxelMaterial::computeShader:
//
//     #version 450
//     #extension GL_GOOGLE_include_directive : require
//     #include "bricklight/voxelize_compute.glsl"
//     vec3 blVoxelEmittance(BlVoxelFragment f) { return /* the same as the fragment shader's */; }
//
// The contract is voxelize.glsl's (BL_VOXEL_OPACITY_ONLY, BL_VOXEL_MULTI_BOUNCE and BL_VOXEL_COVERAGE too: the
// coverage hook is evaluated at the same points as in the draws), with fewer slots left
// to the function: constants 0–1, textures, read buffers 0–3, storage buffers 0–4 and 6, images 0–6. Ours take
// constants 2 (the instance and its mesh) and 3 (the material), read buffers 4–6 (the mesh's positions,
// normals and indices) and 7 (the frame), storage buffers 5 (the list of drawn triangles) and 7, image 7.
// BlVoxelFragment is the same, except that normal, user0 and user1 are interpolated by the triangle's
// barycentric weights at the pixel's centre instead of by the rasterizer (equal up to rounding).
#ifndef BRICKLIGHT_VOXELIZE_COMPUTE_GLSL
#define BRICKLIGHT_VOXELIZE_COMPUTE_GLSL

#define BL_VOXEL_COMPUTE
#include "bricklight/voxelize.glsl"

layout(local_size_x = 64) in;

BL_CONSTANTS(3) uniform BlVoxelMaterial {
    vec4 material;  // x thickness in voxels of the level, y opacity (0..1), z two-sided (0 or 1)
} blVoxelMaterial;
// The instance (vct/voxelize_mesh_body.glsl's VoxelInstance) and where its mesh lies in the read buffers.
BL_CONSTANTS(2) uniform BlVoxelMeshInstance {
    mat4 transform;
    vec4 normalRows[3];  // the inverse transpose's rows (xyz)
    vec4 user0, user1;
    uvec4 positions;  // x first word, y stride in words, z triangles of this dispatch, w 1: the mesh has normals
    uvec4 normals;    // x first word, y stride in words, z vertices, w first triangle of this dispatch
    uvec4 indices;    // x first word; y first word of the instance's drawn-triangle list, z the word of its count
    vec4 split;       // x: the largest extent (finest voxels, any axis) of a triangle voxelized here
} blVoxelMesh;
BL_READ_BUFFER(4) BlVoxelPositions { uint words[]; } blVoxelPositions;
BL_READ_BUFFER(5) BlVoxelNormals { uint words[]; } blVoxelNormals;
BL_READ_BUFFER(6) BlVoxelIndices { uint words[]; } blVoxelIndices;
BL_STORAGE_BUFFER(5) BlVoxelDrawn { uint words[]; } blVoxelDrawn;  // indices of the triangles left to the draw

vec3 blVoxelLoad3(uint first, uint stride, uint vertex, bool normals) {
    uint w = first + stride * vertex;
    uvec3 bits = normals ? uvec3(blVoxelNormals.words[w], blVoxelNormals.words[w + 1u], blVoxelNormals.words[w + 2u])
                         : uvec3(blVoxelPositions.words[w], blVoxelPositions.words[w + 1u], blVoxelPositions.words[w + 2u]);
    return uintBitsToFloat(bits);
}

void main() {
    uint triangle = gl_GlobalInvocationID.x;
    if (triangle >= blVoxelMesh.positions.z) return;
    triangle += blVoxelMesh.normals.w;
    // Per-invocation data in every condition on the constants (docs/notes/soak.md: lavapipe compiles a variant
    // per dispatch for a branch on constants alone).
    bool hasNormals = blVoxelMesh.positions.w != 0u && triangle != 0xffffffffu;
    uint corner[3];
    vec3 world[3], normal[3];
    for (int i = 0; i < 3; ++i) {
        corner[i] = blVoxelIndices.words[blVoxelMesh.indices.x + 3u * triangle + uint(i)];
        // An index out of range (an application's buffer) drops the triangle rather than read past the mesh.
        if (corner[i] >= blVoxelMesh.normals.z) return;
        // As vct/voxelize_mesh_body.glsl's vertex shader computes them.
        vec3 position = blVoxelLoad3(blVoxelMesh.positions.x, blVoxelMesh.positions.y, corner[i], false);
        precise vec4 w = blVoxelMesh.transform * vec4(position, 1.0);  // as voxelize_mesh_body.glsl, bit for bit
        world[i] = w.xyz / w.w;
        normal[i] = vec3(0.0);
        if (hasNormals) {
            vec3 n = blVoxelLoad3(blVoxelMesh.normals.x, blVoxelMesh.normals.y, corner[i], true);
            normal[i] = vec3(dot(blVoxelMesh.normalRows[0].xyz, n), dot(blVoxelMesh.normalRows[1].xyz, n), dot(blVoxelMesh.normalRows[2].xyz, n));
        }
    }

    // Big triangles (many pixels for one invocation) go to the draw, all levels at once: the level-0 extent
    // bounds every level's pixels. NaN compares false: such a triangle stays here and the setup drops it.
    vec3 lo = min(min(world[0], world[1]), world[2]), hi = max(max(world[0], world[1]), world[2]);
    if (any(greaterThan(hi - lo, vec3(blVoxelMesh.split.x * blVctFrame.scales.x)))) {
        if (gl_WorkGroupID.y == 0u) {
            uint at = atomicAdd(blVoxelDrawn.words[blVoxelMesh.indices.z], 3u);
            for (int i = 0; i < 3; ++i) blVoxelDrawn.words[blVoxelMesh.indices.y + at + uint(i)] = corner[i];
        }
        return;
    }

    // One invocation per triangle and level: the dispatch's groups in y are the levels. (A loop over the levels
    // in one invocation wrote less than the draws on GL/llvmpipe, Mesa 22.3, for a ~90-voxel triangle, not
    // understood; one level per invocation matches, and spreads a big triangle's levels over threads.)
    uint level = gl_WorkGroupID.y;
    BlVoxelTriangle t;
    if (!blVoxelSetupTriangle(world, level, blVoxelMaterial.material, t)) return;
    // The pixels whose square may touch the bounding box (blVoxelPixel tests them), within the level.
    int resolution = int(blVctFrame.params.x);
    ivec2 first = max(ivec2(floor(t.bounds.xy)) - 1 + t.offset.xy, ivec2(0));
    ivec2 last = min(ivec2(floor(t.bounds.zw)) + t.offset.xy, ivec2(resolution - 1));
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
            ivec2 pixel = ivec2(x, y);
            vec3 weight = blVoxelWeights(t, vec2(pixel - t.offset.xy) + 0.5);
            blVoxelCount(BL_VCT_COUNT_FRAGMENTS, 1u);
            // The instance's user vectors are the same at every vertex: no gradient for the coverage hook's points.
            blVoxelPixel(t, pixel, weight.x * normal[0] + weight.y * normal[1] + weight.z * normal[2],
                         (weight.x + weight.y + weight.z) * blVoxelMesh.user0, (weight.x + weight.y + weight.z) * blVoxelMesh.user1,
                         BlVoxelUserGradient(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0)));
        }
}

#endif
