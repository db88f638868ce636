#version 450
#extension GL_GOOGLE_include_directive : require
// Voxel AO (a clip-map without emittance) of a scene with alpha-tested materials: opacity only, weighted by the
// materials' coverage (voxel_alpha.glsl). Scenes without them use the clip-map's own opacity shader.
#define BL_VOXEL_OPACITY_ONLY
#define BL_VOXEL_COVERAGE
#include "bricklight/voxelize.glsl"
#define BL_SCENE_TEXTURES
#include "scene_trace.glsl"
#include "voxel_alpha.glsl"
