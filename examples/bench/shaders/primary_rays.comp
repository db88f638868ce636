#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
// Primary rays of a pinhole camera, one per pixel: the benchmark's trace-throughput measure. Writes the
// hit distance so that the work cannot be optimised away.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params { mat4 inverseViewProjection; vec4 eye; uvec4 size; } params;
BL_STORAGE_BUFFER(0) Depth { float depth[]; };

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(params.size.xy) * 2.0 - 1.0;
    vec4 farPoint = params.inverseViewProjection * vec4(ndc.x, -ndc.y, 1.0, 1.0);
    vec3 direction = normalize(farPoint.xyz / farPoint.w - params.eye.xyz);
    BlSdfHit hit = blSdfTrace(blSdfMakeRay(params.eye.xyz, direction, 0.0, 1e30));
    depth[pixel.y * params.size.x + pixel.x] = hit.hit ? hit.t : -1.0;
}
