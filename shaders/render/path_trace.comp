#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Reference path tracer: unbiased path tracing of the scene's triangles (BVH built on the CPU) with
// Lambertian materials, one-sided emitters, a uniform sky and a sun. Direct light from emitters and the
// sun by next-event estimation only (emission is counted on camera rays; a path that hits an emitter
// later carries its reflected light but not its emission, which NEE has already counted), light from the
// sky by escaping paths. Russian roulette from the fourth vertex on. Each dispatch adds `samples` samples
// per pixel to running sums of the AOVs:
//   0 combined   radiance along the camera ray
//   1 direct     emission seen + light that reaches the primary hit straight from an emitter, the sun or the sky
//   2 indirect   indirect diffuse at the primary hit: incoming radiance that has bounced at least once,
//                as irradiance / pi (a white Lambertian surface's outgoing radiance), before albedo
//   3 albedo     4 normal (world, facing the camera)     5 depth (view-space distance along the camera axis)
// so that combined = direct + albedo * indirect for Lambertian scenes.
layout(local_size_x = 8, local_size_y = 8) in;

BL_CONSTANTS(0) uniform Params {
    vec4 eye;            // xyz; w: minimum ray distance (self-intersection offset)
    vec4 forward;        // xyz camera axis; w: tan(vertical fov / 2)
    vec4 right;          // xyz; w: aspect (width / height)
    vec4 up;             // xyz
    vec4 sky;            // rgb radiance
    vec4 sunDirection;   // xyz towards the sun
    vec4 sunIrradiance;  // rgb
    uvec4 size;          // xy image size, z first sample index, w samples in this dispatch
    uvec4 counts;        // x light count, y seed, z max bounces
    vec4 lightWeight;    // x total emitter weight
} params;
BL_READ_BUFFER(0) Triangles { vec4 triangles[]; };   // 3 per triangle; v0.w = material (bits)
BL_READ_BUFFER(1) Nodes { vec4 nodes[]; };           // 2 per node: min, rightOrFirst; max, count
BL_READ_BUFFER(2) Materials { vec4 materials[]; };   // 2 per material: albedo, roughness; emission, metalness
BL_READ_BUFFER(3) Lights { vec4 lights[]; };         // triangle (bits), area, cumulative weight, weight
BL_STORAGE_BUFFER(0) Accumulation { vec4 accumulated[]; };  // 6 AOVs x pixels: sums, w = samples

const float PI = 3.14159265358979;

uint rngState;
uint pcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
float rand() {
    rngState = pcg(rngState);
    return float(rngState >> 8) * (1.0 / 16777216.0);
}

struct Hit {
    float t;
    uint triangle;
};

// Nearest hit in (tMin, tMax), or any hit when `anyHit` (shadow rays).
bool traceRay(vec3 o, vec3 d, float tMin, float tMax, bool anyHit, out Hit hit) {
    vec3 inv = 1.0 / mix(d, vec3(1e-30), lessThan(abs(d), vec3(1e-30)));
    uint stack[48];
    uint top = 0u;
    uint node = 0u;
    hit.t = tMax;
    hit.triangle = 0xFFFFFFFFu;
    while (true) {
        vec4 a = nodes[2u * node], b = nodes[2u * node + 1u];
        vec3 t0 = (a.xyz - o) * inv, t1 = (b.xyz - o) * inv;
        float tn = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), tMin));
        float tf = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), hit.t));
        if (tn <= tf) {
            uint count = floatBitsToUint(b.w);
            uint link = floatBitsToUint(a.w);
            if (count == 0u) {
                // Inner: the left child follows; visit it, keep the right one.
                if (top < 48u) stack[top++] = link;
                node = node + 1u;
                continue;
            }
            for (uint i = link; i < link + count; ++i) {
                vec3 v0 = triangles[3u * i].xyz, e1 = triangles[3u * i + 1u].xyz - v0, e2 = triangles[3u * i + 2u].xyz - v0;
                vec3 p = cross(d, e2);
                float det = dot(e1, p);
                if (abs(det) < 1e-20) continue;
                float invDet = 1.0 / det;
                vec3 s = o - v0;
                float u = dot(s, p) * invDet;
                if (u < 0.0 || u > 1.0) continue;
                vec3 q = cross(s, e1);
                float v = dot(d, q) * invDet;
                if (v < 0.0 || u + v > 1.0) continue;
                float t = dot(e2, q) * invDet;
                if (t > tMin && t < hit.t) {
                    hit.t = t;
                    hit.triangle = i;
                    if (anyHit) return true;
                }
            }
        }
        if (top == 0u) break;
        node = stack[--top];
    }
    return hit.triangle != 0xFFFFFFFFu;
}

vec3 triangleNormal(uint tri) {
    vec3 v0 = triangles[3u * tri].xyz;
    return normalize(cross(triangles[3u * tri + 1u].xyz - v0, triangles[3u * tri + 2u].xyz - v0));
}

vec3 cosineDirection(vec3 n) {
    float r1 = rand(), r2 = rand();
    float phi = 2.0 * PI * r1, s = sqrt(r2);
    vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0, 1, 0)) : cross(n, vec3(1, 0, 0)));
    vec3 b = cross(n, t);
    return normalize(t * (cos(phi) * s) + b * (sin(phi) * s) + n * sqrt(max(0.0, 1.0 - r2)));
}

// Light reflected towards the viewer by a Lambertian surface (albedo, normal n facing the viewer) at p,
// straight from the emitters (one sample, chosen by weight = area x luminance) and the sun.
vec3 directLight(vec3 p, vec3 n, vec3 albedo, float eps) {
    vec3 sum = vec3(0.0);
    if (params.counts.x > 0u) {
        float u = rand() * params.lightWeight.x;
        uint lo = 0u, hi = params.counts.x - 1u;
        while (lo < hi) {
            uint mid = (lo + hi) >> 1;
            if (lights[mid].z < u) lo = mid + 1u; else hi = mid;
        }
        vec4 light = lights[lo];
        uint tri = floatBitsToUint(light.x);
        float r1 = rand(), r2 = rand();
        float sr = sqrt(r1);
        vec3 v0 = triangles[3u * tri].xyz, v1 = triangles[3u * tri + 1u].xyz, v2 = triangles[3u * tri + 2u].xyz;
        vec3 q = v0 * (1.0 - sr) + v1 * (sr * (1.0 - r2)) + v2 * (sr * r2);
        vec3 toLight = q - p;
        float dist2 = dot(toLight, toLight);
        float dist = sqrt(dist2);
        vec3 l = toLight / dist;
        vec3 nl = triangleNormal(tri);
        float cosL = dot(nl, -l), cosP = dot(n, l);
        if (cosL > 0.0 && cosP > 0.0) {
            Hit h;
            if (!traceRay(p, l, eps, dist * (1.0 - 1e-4), true, h)) {
                uint material = floatBitsToUint(triangles[3u * tri].w);
                vec3 emission = materials[2u * material + 1u].rgb;
                // pdf = (weight / total) / area
                sum += albedo / PI * emission * cosP * cosL / dist2 * light.y * params.lightWeight.x / light.w;
            }
        }
    }
    float cosS = dot(n, params.sunDirection.xyz);
    if (cosS > 0.0 && any(greaterThan(params.sunIrradiance.rgb, vec3(0.0)))) {
        Hit h;
        if (!traceRay(p, params.sunDirection.xyz, eps, 1e30, true, h)) sum += albedo / PI * params.sunIrradiance.rgb * cosS;
    }
    return sum;
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    uint pixelIndex = pixel.y * params.size.x + pixel.x;
    uint pixelCount = params.size.x * params.size.y;
    float eps = params.eye.w;
    vec3 sums[6] = vec3[6](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
    for (uint s = 0u; s < params.size.w; ++s) {
        rngState = pcg(pixelIndex ^ pcg(params.size.z + s + pcg(params.counts.y)));
        // Camera ray through a jittered point of the pixel (image origin top-left).
        vec2 ndc = (vec2(pixel) + vec2(rand(), rand())) / vec2(params.size.xy) * 2.0 - 1.0;
        vec3 dir = normalize(params.forward.xyz + params.right.xyz * (ndc.x * params.forward.w * params.right.w) -
                             params.up.xyz * (ndc.y * params.forward.w));
        vec3 origin = params.eye.xyz;
        Hit hit;
        if (!traceRay(origin, dir, 0.0, 1e30, false, hit)) {
            sums[0] += params.sky.rgb;
            sums[1] += params.sky.rgb;
            continue;
        }
        vec3 p = origin + dir * hit.t;
        vec3 ng = triangleNormal(hit.triangle);
        bool front = dot(ng, dir) < 0.0;
        vec3 n = front ? ng : -ng;
        uint material = floatBitsToUint(triangles[3u * hit.triangle].w);
        vec3 albedo = materials[2u * material].rgb;
        vec3 emission = front ? materials[2u * material + 1u].rgb : vec3(0.0);
        sums[3] += albedo;
        sums[4] += n;
        sums[5] += vec3(dot(p - origin, params.forward.xyz));
        vec3 direct = emission + directLight(p, n, albedo, eps);
        vec3 radiance = direct;
        // The first bounce: escaping to the sky is still direct light at the primary hit.
        vec3 indirect = vec3(0.0);
        vec3 throughput = albedo;    // cosine sampling: brdf * cos / pdf = albedo
        vec3 relative = vec3(1.0);   // throughput after the primary hit, without its albedo
        vec3 d = cosineDirection(n);
        for (uint bounce = 1u; bounce <= params.counts.z; ++bounce) {
            if (!traceRay(p, d, eps, 1e30, false, hit)) {
                if (bounce == 1u) direct += throughput * params.sky.rgb;
                else indirect += relative * params.sky.rgb;
                radiance += throughput * params.sky.rgb;
                break;
            }
            p = p + d * hit.t;
            ng = triangleNormal(hit.triangle);
            n = dot(ng, d) < 0.0 ? ng : -ng;
            material = floatBitsToUint(triangles[3u * hit.triangle].w);
            albedo = materials[2u * material].rgb;
            vec3 light = directLight(p, n, albedo, eps);
            radiance += throughput * light;
            indirect += relative * light;
            if (bounce >= 3u) {
                float keep = min(max(throughput.r, max(throughput.g, throughput.b)), 0.95);
                if (rand() >= keep) break;
                throughput /= keep;
                relative /= keep;
            }
            throughput *= albedo;
            relative *= albedo;
            d = cosineDirection(n);
        }
        sums[0] += radiance;
        sums[1] += direct;
        sums[2] += indirect;
    }
    for (uint a = 0u; a < 6u; ++a) accumulated[a * pixelCount + pixelIndex] += vec4(sums[a], float(params.size.w));
}
