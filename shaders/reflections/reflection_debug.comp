#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The reflection classifier's debug view (reflections::ReflectionClassifier::debugView), per tile: 0 its class (green
// screen-space first, yellow checkerboard, red SDF only; a third as bright without rays), 1 its rays (green
// screen-space, red SDF, /64), 2 its hit counter (green new hits, red new misses, blue previous hits, /64).
// Tile borders are darkened so that tiles read apart.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#include "reflection_params.glsl"
BL_IMAGE(0, r32ui) uniform readonly uimage2D tileInfo;
BL_IMAGE(1, r32ui) uniform readonly uimage2D counter;
BL_IMAGE(2, rgba8) uniform writeonly image2D outputImage;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), params.size.xy))) return;
    ivec2 tile = pixel / 8;
    uint info = imageLoad(tileInfo, tile).x;
    uint hits = imageLoad(counter, tile).x;
    uint cls = info & 3u, screenRays = (info >> 8u) & 0xFFu, sdfRays = (info >> 16u) & 0xFFu;
    vec3 classColour = cls == 0u ? vec3(0.1, 0.9, 0.1) : cls == 1u ? vec3(0.9, 0.9, 0.1) : vec3(0.9, 0.1, 0.1);
    classColour *= screenRays + sdfRays > 0u ? 1.0 : 0.33;
    vec3 rayColour = vec3(float(sdfRays), float(screenRays), 0.0) / 64.0;
    vec3 counterColour = vec3(float((hits >> 8u) & 0xFFu), float(hits & 0xFFu), float((hits >> 16u) & 0xFFu)) / 64.0;
    uint mode = params.debug.x;
    vec3 colour = mode == 0u ? classColour : mode == 1u ? rayColour : counterColour;
    bool border = any(equal(pixel & 7, ivec2(0)));
    imageStore(outputImage, pixel, vec4(clamp(colour, 0.0, 1.0) * (border ? 0.6 : 1.0), 1.0));
}
