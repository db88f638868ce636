#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Reference path tracer: unbiased path tracing of the scene's triangles (BVH built on the CPU) with
// Lambertian + GGX materials (scene_trace.glsl's BRDF), one-sided emitters, a uniform sky and a sun. Direct light from emitters and the
// sun by next-event estimation only (emission is counted on camera rays; a path that hits an emitter
// later carries its reflected light but not its emission, which NEE has already counted), light from the
// sky by escaping paths (past the last bounce too); directions sampled from the BRDF. Russian roulette from the fourth vertex on. Each dispatch adds `samples` samples
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
// Where the camera ray's first hit takes the glass lobe, the pixel has no diffuse surface of its own: direct =
// combined (all it shows comes through or off the glass), indirect = 0, albedo = 0; normal, depth and ao are
// the glass surface's. Light that reaches an opaque primary hit through glass is indirect (it was refracted).
// Row 7 of the accumulation counts, per pixel, samples left out of the sums and of their count (w): x those a
// CPU driver's loop limit cut short (loopBudgetSpent; PathTracer::samplesCutShort()), y those whose radiance
// came out non-finite (PathTracer::samplesNonFinite()): one such sample would poison its pixel's whole mean.
layout(local_size_x = 8, local_size_y = 8) in;

// Slot 2, not 0: lavapipe (Mesa 22.3) specializes a compute shader on the values in its uniform block 0 that steer
// control flow, and with this block there it compiled and kept a new variant per dispatch (2.6 MB and about 15 ms
// each; 1,024 dispatches took 2.8 GB, even with the first sample index held constant). At slot 2 it compiles once.
BL_CONSTANTS(2) uniform Params {
    vec4 eye;            // xyz; w: the ao AOV's range
    vec4 forward;        // xyz camera axis; w: tan(vertical fov / 2)
    vec4 right;          // xyz; w: aspect (width / height)
    vec4 up;             // xyz; w: 1 = jitter samples over the pixel, 0 = pixel centres
    uvec4 size;          // xy image size, z first sample index, w samples in this dispatch
} params;
BL_STORAGE_BUFFER(0) Accumulation { vec4 accumulated[]; };  // 7 AOVs x pixels: sums, w = samples
#include "scene_trace.glsl"

// By the bits, which no fast-math compilation folds away (isnan/isinf may be, as `x != x`): inf or NaN.
bool allFinite(vec3 x) {
    uvec3 exponent = floatBitsToUint(x) & 0x7F800000u;
    return all(notEqual(exponent, uvec3(0x7F800000u)));
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    uint pixelIndex = pixel.y * params.size.x + pixel.x;
    uint pixelCount = params.size.x * params.size.y;
    float eps = sceneLight.lightWeight.y;
    vec3 sums[7] = vec3[7](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
    uint finished = 0u, nonFinite = 0u;
    for (uint s = 0u; s < params.size.w; ++s) {
        vec3 aovs[7] = vec3[7](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
        rngState = pcg(pixelIndex ^ pcg(params.size.z + s + pcg(sceneLight.counts.y)));
        // Camera ray through a jittered point of the pixel (image origin top-left).
        vec2 jitter = vec2(rand(), rand());
        if (params.up.w == 0.0) jitter = vec2(0.5);
        vec2 ndc = (vec2(pixel) + jitter) / vec2(params.size.xy) * 2.0 - 1.0;
        vec3 d = normalize(params.forward.xyz + params.right.xyz * (ndc.x * params.forward.w * params.right.w) -
                           params.up.xyz * (ndc.y * params.forward.w));
        vec3 origin = params.eye.xyz;
        vec3 radiance = vec3(0.0), direct = vec3(0.0), indirect = vec3(0.0);
        vec3 throughput = vec3(1.0);
        vec3 relative = vec3(0.0);  // indirect diffuse at the primary hit per unit radiance arriving at this vertex
        bool countEmission = true;  // camera rays, and rays a glass vertex sampled
        bool glassPixel = false;
        // Vertex k = 0 is the primary hit; the ray of vertex k leaves vertex k − 1.
        // One vertex past the last bounce (counts.z) the ray only looks for the sky: the last vertex's light includes
        // the sky as it includes the sun and the emitters (next-event estimation), so that a path of n bounces carries
        // all of the light that reaches it after n reflections (maxBounces = 1 is then one bounce of every light).
        for (uint k = 0u; k <= sceneLight.counts.z + 1u; ++k) {
            Hit hit;
            if (!traceRay(origin, d, k == 0u ? 0.0 : eps, 1e30, false, hit)) {
                // The camera ray, or the primary hit's ray, escaping to the sky is direct light.
                if (k <= 1u) direct += throughput * sceneLight.sky.rgb;
                else indirect += relative * sceneLight.sky.rgb;
                radiance += throughput * sceneLight.sky.rgb;
                if (k == 0u) aovs[6] += vec3(1.0);
                break;
            }
            if (k > sceneLight.counts.z) break;
            vec3 p = origin + d * hit.t;
            vec3 ng = triangleNormal(hit.triangle);
            bool front = dot(ng, d) < 0.0;
            ng = front ? ng : -ng;  // towards the ray's origin
            vec3 n = shadingNormal(hit.triangle, hit.bary, ng);
            uint material = floatBitsToUint(triangles[3u * hit.triangle].w);
            Surface surface = surfaceAt(material, hit.triangle, hit.bary);
            vec3 v = -d;
            if (k == 0u) {
                aovs[4] += n;
                aovs[5] += vec3(dot(p - origin, params.forward.xyz));
                // AO from a stream of its own, so that the other AOVs draw the same numbers as without it. Always
                // traced (no flag: a short any-hit ray); a range of 0 or below eps makes it 1.
                uint pathRng = rngState;
                rngState = pcg(pathRng ^ 0x9E3779B9u);
                Hit occluder;
                aovs[6] += vec3(traceRay(p, cosineDirection(n), eps, params.eye.w, true, occluder) ? 0.0 : 1.0);
                rngState = pathRng;
            }
            if (countEmission && front) {
                vec3 emission = materials[4u * material + 1u].rgb;
                radiance += throughput * emission;
                if (k == 0u) direct += emission; else indirect += relative * emission;
            }
            // The glass lobe with probability `transmission` (no draw for opaque or clear glass).
            float transmission = glassTransmission(material);
            bool glass = transmission > 0.0 && (transmission >= 1.0 || rand() < transmission);
            if (k == 0u) {
                glassPixel = glass;
                aovs[3] += glass ? vec3(0.0) : surface.baseColor;
            }
            if (!glass) {
                vec3 light = directLight(p, n, v, surface, eps);
                radiance += throughput * light;
                if (k == 0u) direct += light; else indirect += relative * light;
            }
            if (k >= 3u) {
                float keep = min(max(throughput.r, max(throughput.g, throughput.b)), 0.95);
                if (rand() >= keep) break;
                throughput /= keep;
                relative /= keep;
            }
            vec3 next, weight;
            if (glass) {
                float w;
                if (!sampleGlass(n, ng, v, front, surface.roughness, glassIor(material), next, w)) break;
                weight = vec3(w);
            } else if (!sampleBrdf(surface, n, v, next, weight)) {
                break;
            }
            // Indirect diffuse at the primary hit, as irradiance / pi: cos / (pi pdf) per unit incoming radiance
            // (1 for a Lambertian surface's cosine sampling).
            if (k == 0u && !glass) relative = vec3(max(dot(n, next), 0.0) / (PI * brdfPdf(surface, n, v, next)));
            else relative *= weight;
            throughput *= weight;
            countEmission = glass;
            origin = p;
            d = next;
        }
        aovs[0] += radiance;
        aovs[1] += glassPixel ? radiance : direct;
        aovs[2] += glassPixel ? vec3(0.0) : indirect;
        // Spent now: this sample's loops (a traversal, its bounces) may have ended early, and so will every later one.
        if (loopBudgetSpent()) break;
        if (!allFinite(aovs[0]) || !allFinite(aovs[1]) || !allFinite(aovs[2])) {
            ++nonFinite;
            continue;
        }
        for (uint a = 0u; a < 7u; ++a) sums[a] += aovs[a];
        ++finished;
    }
    // `finished`, not the samples asked for: samples left out must not dim the mean.
    for (uint a = 0u; a < 7u; ++a) accumulated[a * pixelCount + pixelIndex] += vec4(sums[a], float(finished));
    accumulated[7u * pixelCount + pixelIndex].xy += vec2(float(params.size.w - finished - nonFinite), float(nonFinite));
}
