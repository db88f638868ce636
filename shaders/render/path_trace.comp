#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Reference path tracer: unbiased path tracing of the scene's triangles (BVH built on the CPU) with
// Lambertian + GGX materials (scene_trace.glsl's BRDF), one-sided emitters, a uniform sky and a sun. Direct light from emitters and the
// sun by next-event estimation only (emission is counted on camera rays; a path that hits an emitter
// later carries its reflected light but not its emission, which NEE has already counted), light from the
// sky by escaping paths; directions sampled from the BRDF. Russian roulette from the fourth vertex on. Each dispatch adds `samples` samples
// per pixel to running sums of the AOVs:
//   0 combined   radiance along the camera ray
//   1 direct     emission seen + light that reaches the primary hit straight from an emitter, the sun or the sky
//   2 indirect   indirect diffuse at the primary hit: incoming radiance that has bounced at least once,
//                as irradiance / pi (a white Lambertian surface's outgoing radiance), before albedo
//   3 albedo     4 normal (world, facing the camera)     5 depth (view-space distance along the camera axis)
//   6 ao         ambient occlusion at the primary hit: 1 if a cosine-weighted ray about the shading normal
//                hits nothing within eye.w (world units), else 0; 1 where the camera ray escapes
// so that combined = direct + albedo * indirect for Lambertian scenes.
// (For glossy surfaces the indirect AOV is still the diffuse irradiance estimate, weighted cos/(pi pdf).)
layout(local_size_x = 8, local_size_y = 8) in;

BL_CONSTANTS(0) uniform Params {
    vec4 eye;            // xyz; w: the ao AOV's range
    vec4 forward;        // xyz camera axis; w: tan(vertical fov / 2)
    vec4 right;          // xyz; w: aspect (width / height)
    vec4 up;             // xyz; w: 1 = jitter samples over the pixel, 0 = pixel centres
    uvec4 size;          // xy image size, z first sample index, w samples in this dispatch
} params;
BL_STORAGE_BUFFER(0) Accumulation { vec4 accumulated[]; };  // 7 AOVs x pixels: sums, w = samples
#define BL_SCENE_TEXTURES
#include "scene_trace.glsl"

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    uint pixelIndex = pixel.y * params.size.x + pixel.x;
    uint pixelCount = params.size.x * params.size.y;
    float eps = sceneLight.lightWeight.y;
    vec3 sums[7] = vec3[7](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
    for (uint s = 0u; s < params.size.w; ++s) {
        rngState = pcg(pixelIndex ^ pcg(params.size.z + s + pcg(sceneLight.counts.y)));
        // Camera ray through a jittered point of the pixel (image origin top-left).
        vec2 jitter = vec2(rand(), rand());
        if (params.up.w == 0.0) jitter = vec2(0.5);
        vec2 ndc = (vec2(pixel) + jitter) / vec2(params.size.xy) * 2.0 - 1.0;
        vec3 dir = normalize(params.forward.xyz + params.right.xyz * (ndc.x * params.forward.w * params.right.w) -
                             params.up.xyz * (ndc.y * params.forward.w));
        vec3 origin = params.eye.xyz;
        Hit hit;
        if (!traceRay(origin, dir, 0.0, 1e30, false, hit)) {
            sums[0] += sceneLight.sky.rgb;
            sums[1] += sceneLight.sky.rgb;
            sums[6] += vec3(1.0);
            continue;
        }
        vec3 p = origin + dir * hit.t;
        vec3 ng = triangleNormal(hit.triangle);
        bool front = dot(ng, dir) < 0.0;
        vec3 n = shadingNormal(hit.triangle, hit.bary, front ? ng : -ng);
        uint material = floatBitsToUint(triangles[3u * hit.triangle].w);
        Surface surface = surfaceAt(material, hit.triangle, hit.bary);
        vec3 emission = front ? materials[3u * material + 1u].rgb : vec3(0.0);
        sums[3] += surface.baseColor;
        sums[4] += n;
        sums[5] += vec3(dot(p - origin, params.forward.xyz));
        // AO from a stream of its own, so that the other AOVs draw the same numbers as without it. Always
        // traced (no flag: a short any-hit ray); a range of 0 or below eps makes it 1.
        uint pathRng = rngState;
        rngState = pcg(pathRng ^ 0x9E3779B9u);
        Hit occluder;
        sums[6] += vec3(traceRay(p, cosineDirection(n), eps, params.eye.w, true, occluder) ? 0.0 : 1.0);
        rngState = pathRng;
        vec3 v = -dir;
        vec3 direct = emission + directLight(p, n, v, surface, eps);
        vec3 radiance = direct;
        vec3 indirect = vec3(0.0);
        vec3 d, throughput;
        if (sampleBrdf(surface, n, v, d, throughput)) {
            // Indirect diffuse at the primary hit, as irradiance / pi: cos / (pi pdf) per unit incoming
            // radiance (1 for a Lambertian surface's cosine sampling).
            vec3 relative = vec3(max(dot(n, d), 0.0) / (PI * brdfPdf(surface, n, v, d)));
            for (uint bounce = 1u; bounce <= sceneLight.counts.z; ++bounce) {
                if (!traceRay(p, d, eps, 1e30, false, hit)) {
                    // The first bounce escaping to the sky is still direct light at the primary hit.
                    if (bounce == 1u) direct += throughput * sceneLight.sky.rgb;
                    else indirect += relative * sceneLight.sky.rgb;
                    radiance += throughput * sceneLight.sky.rgb;
                    break;
                }
                p = p + d * hit.t;
                ng = triangleNormal(hit.triangle);
                n = shadingNormal(hit.triangle, hit.bary, dot(ng, d) < 0.0 ? ng : -ng);
                material = floatBitsToUint(triangles[3u * hit.triangle].w);
                surface = surfaceAt(material, hit.triangle, hit.bary);
                v = -d;
                vec3 light = directLight(p, n, v, surface, eps);
                radiance += throughput * light;
                indirect += relative * light;
                if (bounce >= 3u) {
                    float keep = min(max(throughput.r, max(throughput.g, throughput.b)), 0.95);
                    if (rand() >= keep) break;
                    throughput /= keep;
                    relative /= keep;
                }
                vec3 weight;
                if (!sampleBrdf(surface, n, v, d, weight)) break;
                throughput *= weight;
                relative *= weight;
            }
        }
        sums[0] += radiance;
        sums[1] += direct;
        sums[2] += indirect;
    }
    for (uint a = 0u; a < 7u; ++a) accumulated[a * pixelCount + pixelIndex] += vec4(sums[a], float(params.size.w));
}
