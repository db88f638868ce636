#version 450
#extension GL_GOOGLE_include_directive : require
// Draws the recorded samples of one pixel's cones (cone_samples.comp) over the camera's view: each sample a
// translucent sphere of its diameter, coloured by its cone (the specular cone white; a surface read where the
// distance field stopped a cone yellow), darker where less light gets through to it (its transmittance), in front
// of the G-buffer's surfaces, which show as grey by their normal. The pixel itself is marked with a cross.
#include "trace_common.glsl"
#include "cone_samples_layout.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Probe {
    ivec4 pixel;  // xy: the pixel whose cones were recorded
} probe;
BL_READ_BUFFER(0) ConeSamples { VCT_CONE_SAMPLES_BODY } record;
BL_IMAGE(0, rgba8) uniform writeonly image2D outputImage;

vec3 coneColour(uint cone) {
    if (cone >= 32u) return vec3(1.0);
    float h = fract(float(cone) * 0.61803399);
    return clamp(abs(fract(h + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0) * 0.8 + 0.2;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(trace.size.xy)))) return;
    float depth = texelFetch(gDepth, pixel, 0).r;
    vec3 eye = trace.eye.xyz;
    vec3 far = worldPosition(pixel, 1.0);
    vec3 dir = normalize(far - eye);
    float limit = isSky(depth) ? 1.0e30 : distance(worldPosition(pixel, depth), eye);
    vec3 colour = isSky(depth) ? vec3(0.0) : vec3(0.15 + 0.25 * (0.5 + 0.5 * dot(surfaceNormal(pixel), normalize(vec3(0.3, 0.8, 0.5)))));
    // Translucent spheres (the late samples of a wide cone cover much of the view), their rims stronger, so that
    // every cone's string of samples shows through the others; blended without order (weighted average).
    vec3 sum = vec3(0.0);
    float weights = 0.0, coverage = 0.0;
    for (uint cone = 0u; cone < VCT_RECORDED_CONES; ++cone) {
        uint count = min(record.coneSampleCounts[cone], VCT_MAX_CONE_SAMPLES);
        for (uint i = 0u; i < count; ++i) {
            uint base = (cone * VCT_MAX_CONE_SAMPLES + i) * 3u;
            vec4 sphere = record.coneSamples[base];
            vec3 oc = eye - sphere.xyz;
            float r = 0.5 * sphere.w;
            float b = dot(oc, dir), c = dot(oc, oc) - r * r;
            float disc = b * b - c;
            if (disc < 0.0) continue;
            float t = -b - sqrt(disc);
            if (t <= 0.0 || t >= limit) continue;
            vec3 n = normalize(oc + dir * t);
            float rim = pow(max(1.0 - abs(dot(n, dir)), 0.0), 4.0);
            float alpha = 0.08 + 0.6 * rim;
            float transmittance = record.coneSamples[base + 1u].w;
            bool surface = record.coneSamples[base + 2u].x > 254.5;
            sum += alpha * (surface ? vec3(1.0, 0.9, 0.2) : coneColour(cone)) * (0.3 + 0.7 * transmittance);
            weights += alpha;
            coverage = 1.0 - (1.0 - coverage) * (1.0 - alpha);
        }
    }
    if (weights > 0.0) colour = mix(colour, sum / weights, coverage);
    ivec2 d = abs(pixel - probe.pixel.xy);
    if ((d.x == 0 && d.y <= 4) || (d.y == 0 && d.x <= 4)) colour = vec3(1.0, 0.0, 1.0);
    imageStore(outputImage, pixel, vec4(colour, 1.0));
}
