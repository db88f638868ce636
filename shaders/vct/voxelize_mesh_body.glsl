// Our voxelization vertex shader for vct::VoxelScene's registered meshes (included by voxelize_mesh.vert and
// voxelize_mesh_flat.vert, which defines VCT_MESH_FLAT for meshes without normals: each triangle's own normal
// is used then): the instance's transform to world space, its normal matrix, and its two user vectors for the
// material's blVoxelEmittance.
#include "bricklight/bindings.glsl"
#include "bricklight/voxelize_vertex.glsl"
BL_CONSTANTS(2) uniform VoxelInstance {
    mat4 transform;
    vec4 normalRows[3];  // the inverse transpose's rows (xyz)
    vec4 user0, user1;
} instance;
layout(location = 0) in vec3 position;
#ifndef VCT_MESH_FLAT
layout(location = 1) in vec3 normal;
#endif
BL_VOXEL_VERTEX_OUTPUTS

void main() {
    // precise: the compute voxelizer (vct/voxelize_mesh.comp) transforms the same way, and both must give the same
    // bits for the words to match.
    precise vec4 world = instance.transform * vec4(position, 1.0);
#ifdef VCT_MESH_FLAT
    vec3 n = vec3(0.0);  // the geometry stage's face normal stands in for a zero normal
#else
    vec3 n = vec3(dot(instance.normalRows[0].xyz, normal), dot(instance.normalRows[1].xyz, normal), dot(instance.normalRows[2].xyz, normal));
#endif
    blVoxelVertex(world.xyz / world.w, n, instance.user0, instance.user1);
}
