#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/alpha_pass.glsl"
// The GI alpha pass test's alpha test: vertical stripes across u, each period covered over its first `share`.
BL_CONSTANTS(0) uniform Stripes { vec4 stripes; } stripes;  // x: covered share of a period, y: periods across u

bool blAlphaPresent(BlAlphaFragment f) { return fract(f.user.x * stripes.stripes.y) < stripes.stripes.x; }
