#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Voxelization, geometry stage (vct::Clipmap::voxelizationState): one invocation per clip-map level projects the
// triangle along its dominant axis into that level's voxel grid. Every level has the same resolution, so one
// resolution² viewport serves all of them: the level is a flat output, not a viewport index.
//
// Neither lavapipe nor llvmpipe has conservative rasterization, and we want no triangle lost however small:
// the triangle's 2D bounding box, grown by half a pixel, is emitted as a quad, and the fragment shader decides
// per pixel with the triangle's exact edge functions (bricklight/voxelize.glsl). The application's attributes
// are extrapolated linearly over the triangle's plane to the quad's corners. The per-triangle setup is
// blVoxelSetupTriangle, which the compute voxelizer of registered meshes (bricklight/voxelize_compute.glsl)
// shares.
#define BL_VOXEL_SETUP_ONLY
#include "bricklight/voxelize.glsl"
layout(triangles, invocations = 8) in;
layout(triangle_strip, max_vertices = 4) out;

BL_CONSTANTS(3) uniform BlVoxelMaterial {
    vec4 material;  // x thickness in voxels of the level, y opacity (0..1), z two-sided (0 or 1)
} blVoxelMaterial;

layout(location = 0) in vec3 blVoxelNormalIn[];
layout(location = 1) in vec4 blVoxelUser0In[];
layout(location = 2) in vec4 blVoxelUser1In[];

// BlVoxelTriangle's fields, flat (bricklight/voxelize.glsl reads them back).
layout(location = 0) out vec3 blVoxelNormalGs;
layout(location = 1) out vec4 blVoxelUser0Gs;
layout(location = 2) out vec4 blVoxelUser1Gs;
layout(location = 3) flat out vec4 blVoxelEdge0;
layout(location = 4) flat out vec4 blVoxelEdge1;
layout(location = 5) flat out vec4 blVoxelEdge2;
layout(location = 6) flat out vec4 blVoxelPlane;
layout(location = 7) flat out vec4 blVoxelBounds;
layout(location = 8) flat out vec4 blVoxelDepth;
layout(location = 9) flat out ivec4 blVoxelLevelAxis;
layout(location = 10) flat out vec3 blVoxelFaceNormal;
layout(location = 11) flat out ivec3 blVoxelOffset;

void main() {
    uint level = uint(gl_InvocationID);
    vec3 world[3];
    for (int i = 0; i < 3; ++i) world[i] = gl_in[i].gl_Position.xyz;
    BlVoxelTriangle t;
    if (!blVoxelSetupTriangle(world, level, blVoxelMaterial.material, t)) return;
    float resolution = float(blVctFrame.params.x);

    // Every pixel whose square touches the bounding box has its centre inside the quad (with a margin, so that
    // the rasterizer's rules at edges never matter).
    const float grow = 0.5 + 1.0 / 64.0;
    vec2 uvLo = t.bounds.xy, uvHi = t.bounds.zw;
    vec2 corners[4] = vec2[4](vec2(uvLo.x - grow, uvLo.y - grow), vec2(uvHi.x + grow, uvLo.y - grow),
                              vec2(uvLo.x - grow, uvHi.y + grow), vec2(uvHi.x + grow, uvHi.y + grow));
    for (int c = 0; c < 4; ++c) {
        vec3 weight = blVoxelWeights(t, corners[c]);
        blVoxelNormalGs = weight.x * blVoxelNormalIn[0] + weight.y * blVoxelNormalIn[1] + weight.z * blVoxelNormalIn[2];
        blVoxelUser0Gs = weight.x * blVoxelUser0In[0] + weight.y * blVoxelUser0In[1] + weight.z * blVoxelUser0In[2];
        blVoxelUser1Gs = weight.x * blVoxelUser1In[0] + weight.y * blVoxelUser1In[1] + weight.z * blVoxelUser1In[2];
        blVoxelEdge0 = t.edge[0];
        blVoxelEdge1 = t.edge[1];
        blVoxelEdge2 = t.edge[2];
        blVoxelPlane = t.plane;
        blVoxelBounds = t.bounds;
        blVoxelDepth = t.depth;
        blVoxelLevelAxis = t.levelAxis;
        blVoxelFaceNormal = t.faceNormal;
        blVoxelOffset = t.offset;
        gl_Position = vec4((corners[c] + vec2(t.offset.xy)) / resolution * 2.0 - 1.0, 0.5, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
