#version 450
#extension GL_GOOGLE_include_directive : require
// Reprojected texels carried without the parallax test (ContextFlags::NoProbeParallax).
#include "fill_probes_body.glsl"
