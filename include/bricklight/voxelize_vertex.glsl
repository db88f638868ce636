// The vertex shader an application writes for voxelization draws (vct::Clipmap::voxelizationState): it
// declares BL_VOXEL_VERTEX_OUTPUTS and calls blVoxelVertex once with the vertex in world space. Our geometry
// shader projects each triangle into every level; the normal and the two user vectors reach the
// application's blVoxelEmittance (bricklight/voxelize.glsl) interpolated over the triangle's plane.
#ifndef BRICKLIGHT_VOXELIZE_VERTEX_GLSL
#define BRICKLIGHT_VOXELIZE_VERTEX_GLSL

#define BL_VOXEL_VERTEX_OUTPUTS                        \
    layout(location = 0) out vec3 blVoxelNormalOut;    \
    layout(location = 1) out vec4 blVoxelUser0Out;     \
    layout(location = 2) out vec4 blVoxelUser1Out;

// worldNormal: the shading normal (it also says which side of a one-sided surface emits); user0/user1: any
// data the emittance function wants (texture coordinates, material ids...).
#define blVoxelVertex(worldPosition, worldNormal, user0, user1) \
    do {                                                         \
        gl_Position = vec4((worldPosition), 1.0);                \
        blVoxelNormalOut = (worldNormal);                        \
        blVoxelUser0Out = (user0);                               \
        blVoxelUser1Out = (user1);                               \
    } while (false)

#endif
