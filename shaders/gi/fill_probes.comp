#version 450
#extension GL_GOOGLE_include_directive : require
// Reprojected texels whose light lies in another direction from the new probe traced instead of their turn, or emptied
// (reproject_probes.comp).
#define GI_PROBE_PARALLAX
#include "fill_probes_body.glsl"
