#version 450
#extension GL_GOOGLE_include_directive : require
// Hits of surfaces no view has lit read the light of a voxel clip-map (gi::DispatchDesc::unseenLight).
#define GI_UNSEEN_FROM_VCT
#include "fill_probes_body.glsl"
