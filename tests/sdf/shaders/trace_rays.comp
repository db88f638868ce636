#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
// Traces a buffer of rays through the public API and writes the hits, for tests and the benchmark.
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Params { uint rayCount; uint startCascade; uint endCascade; float tMax; } params;
BL_READ_BUFFER(0) Rays { vec4 rays[]; };  // origin.xyz, tMin; direction.xyz, alpha-tested hits to go past
// t (or -1 on a miss), cascade, iterations, brick; normal.xyz, hits gone past + 0.5 if the last is alpha-tested
BL_STORAGE_BUFFER(0) Hits { vec4 hits[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.rayCount) return;
    vec4 a = rays[2u * i], b = rays[2u * i + 1u];
    BlSdfRay ray = blSdfMakeRay(a.xyz, b.xyz, a.w, params.tMax);
    ray.startCascade = params.startCascade;
    ray.endCascade = params.endCascade;
    BlSdfHit hit = blSdfTrace(ray);
    uint passed = 0u;
    for (; hit.hit && hit.alphaTested && passed < uint(b.w); ++passed) {
        ray = blSdfContinueRay(ray, hit);
        hit = blSdfTrace(ray);
    }
    hits[2u * i] = vec4(hit.hit ? hit.t : -1.0, float(hit.cascade), float(hit.iterations), uintBitsToFloat(hit.brickId));
    hits[2u * i + 1u] = vec4(hit.normal, float(passed) + (hit.hit && hit.alphaTested ? 0.5 : 0.0));
}
