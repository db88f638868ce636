#version 450
#extension GL_GOOGLE_include_directive : require
// Traces the cones of a buffer through the clip-map (bricklight/cone_trace.glsl, Clipmap::traceBindings): how
// tests check what cones see.
#include "bricklight/bindings.glsl"
#include "bricklight/cone_trace.glsl"
layout(local_size_x = 64) in;
struct ConeIn {
    vec4 origin;     // xyz, w cone factor
    vec4 direction;  // xyz, w ambient range
};
BL_READ_BUFFER(0) Cones { ConeIn cones[]; };
BL_STORAGE_BUFFER(0) Results { vec4 results[]; };  // per cone: radiance, then (ambient, final opacity, samples, 0)

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(cones.length())) return;
    BlCone c = blDefaultCone(cones[i].origin.xyz, normalize(cones[i].direction.xyz), cones[i].origin.w);
    c.ambientRange = cones[i].direction.w;
    BlConeResult r = blTraceCone(c);
    results[2u * i] = vec4(r.radiance, 0.0);
    results[2u * i + 1u] = vec4(r.ambient, r.finalOpacity, float(r.sampleCount), 0.0);
}
