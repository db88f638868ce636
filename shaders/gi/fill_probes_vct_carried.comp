#version 450
#extension GL_GOOGLE_include_directive : require
// Hits of surfaces no view has lit read the light of a voxel clip-map (gi::DispatchDesc::unseenLight).
// Reprojected texels carried without the parallax test (ContextFlags::NoProbeParallax).
#define GI_UNSEEN_FROM_VCT
#include "fill_probes_body.glsl"
