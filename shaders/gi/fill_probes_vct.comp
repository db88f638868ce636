#version 450
#extension GL_GOOGLE_include_directive : require
// Hits of surfaces no view has lit read the light of a voxel clip-map (gi::DispatchDesc::unseenLight).
// Reprojected texels whose light lies in another direction from the new probe traced instead of their turn, or emptied
// (reproject_probes.comp).
#define GI_PROBE_PARALLAX
#define GI_UNSEEN_FROM_VCT
#include "fill_probes_body.glsl"
