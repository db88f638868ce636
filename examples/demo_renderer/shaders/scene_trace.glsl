// The renderer's scene for ray queries: world triangles in BVH order, the BVH (built on the CPU), materials
// and emitters (GpuScene binds them as read buffers 0..3), and the lighting constants (BL_CONSTANTS(1)).
// Used by the reference path tracer and by the rasterized path's direct lighting.
#ifndef BRICKLIGHT_RENDER_SCENE_TRACE_GLSL
#define BRICKLIGHT_RENDER_SCENE_TRACE_GLSL

BL_CONSTANTS(1) uniform SceneLight {
    vec4 sky;            // rgb radiance
    vec4 sunDirection;   // xyz towards the sun (the centre of its disc); w: the disc's radius at distance 1 (tan of half its angle)
    vec4 sunIrradiance;  // rgb
    uvec4 counts;        // x emitter count, y seed, z max bounces, w point/spot light count
    vec4 lightWeight;    // x total emitter weight, y ray offset
} sceneLight;
BL_READ_BUFFER(0) Triangles { vec4 triangles[]; };   // 3 per triangle; v0.w = material (bits), v1.w = 1 where
                                                     // the material is alpha-tested (traceRay's any-hit test)
BL_READ_BUFFER(1) Nodes { vec4 nodes[]; };           // 2 per node: min, rightOrFirst; max, count
BL_READ_BUFFER(2) Materials { vec4 materials[]; };   // 4 per material: albedo, roughness; emission, metalness;
                                                     // texture layer (-1 none), dielectric F0, transmission, ior;
                                                     // alpha cut-off (0 opaque), base alpha
BL_READ_BUFFER(3) Lights { vec4 lights[]; };         // triangle (bits), area, cumulative weight, weight
BL_READ_BUFFER(4) PointLights { vec4 pointLights[]; };  // 3 per light: position, cos outer; intensity; direction, cos inner
BL_READ_BUFFER(5) TriangleUvs { vec4 triangleUvs[]; };  // 2 per triangle: uv0, uv1; uv2
BL_READ_BUFFER(6) TriangleNormals { vec4 triangleNormals[]; };  // 3 per triangle: shading normals (zero: none)
// Invocations whose rays a CPU driver's loop limit cut short (loopBudgetSpent), counted once each: the renderer
// reports them (RasterRenderer::invocationsCutShort). GpuScene::bind binds it, with Access::Atomic.
BL_STORAGE_BUFFER(4) TraceLoopBudget { uint invocationsCutShort; } traceLoopBudget;
// Always declared (GpuScene::bind binds it): traceRay reads the alpha of alpha-tested materials, so every
// pass that traces rays needs it, not only those that shade with the base colour.
BL_TEXTURE(4) uniform sampler2DArray baseColorTextures;  // one layer per texture (GpuScene::kTextureSize square)

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

// CPU drivers (llvmpipe, lavapipe) end every loop of a shader invocation once all its loops together have run
// 65,535 iterations (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS): from then on each loop stops after one pass, silently,
// and a ray comes back as a miss or a wrong hit. A ray through thousands of overlapping triangles (a stack of
// coincident cut-out cards) needs that many. This loop makes two passes unless the budget is spent (its bound is 2
// at run time, which no compiler can fold into an unrolled pair). GPUs have no such limit: there it always makes two.
bool loopBudgetSpent() {
    uint passes = 0u;
    for (uint i = 0u; i < 2u + (sceneLight.counts.x >> 31u); ++i) ++passes;
    return passes < 2u;
}

// traceRay notes an invocation whose budget ran out, once (later rays of it are as wrong, and one atomic is enough).
bool traceLoopBudgetCounted = false;
void countIfLoopBudgetSpent() {
    if (!traceLoopBudgetCounted && loopBudgetSpent()) {
        traceLoopBudgetCounted = true;
        atomicAdd(traceLoopBudget.invocationsCutShort, 1u);
    }
}

struct Hit {
    float t;
    uint triangle;
    vec2 bary;  // weights of vertices 1 and 2
};

// Texture coordinates at a hit (barycentric weights of vertices 1 and 2).
vec2 hitUv(uint tri, vec2 bary) {
    vec4 a = triangleUvs[2u * tri], b = triangleUvs[2u * tri + 1u];
    return a.xy * (1.0 - bary.x - bary.y) + a.zw * bary.x + b.xy * bary.y;
}

// The any-hit test of alpha-tested materials, the G-buffer's rule (gbuffer.frag): a point whose coverage,
// base alpha x the texture's alpha (level 0), is below the material's cut-off is a hole the ray passes.
bool alphaCutOut(uint tri, vec2 bary) {
    uint material = floatBitsToUint(triangles[3u * tri].w);
    vec2 alphaTest = materials[4u * material + 3u].xy;  // cut-off, base alpha
    float layer = materials[4u * material + 2u].x;
    float alpha = layer >= 0.0 ? textureLod(baseColorTextures, vec3(hitUv(tri, bary), layer), 0.0).a : 1.0;
    return alpha * alphaTest.y < alphaTest.x;
}

// The BVH traversal of traceRay: the nearest triangle in (tMin, tMax), or with `anyHit` the first opaque one
// found. An alpha-tested candidate (v1.w = 1) is, without `testAlpha`, kept as the nearest so far (traceRay tests
// it); with `testAlpha`, tested as it is met: a cut-out point is passed over, anything else is a hit.
bool traverseBvh(vec3 o, vec3 d, float tMin, float tMax, bool anyHit, bool testAlpha, out Hit hit) {
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
                vec4 v1 = triangles[3u * i + 1u];  // w: alpha-tested
                vec3 v0 = triangles[3u * i].xyz, e1 = v1.xyz - v0, e2 = triangles[3u * i + 2u].xyz - v0;
                vec3 p = cross(d, e2);
                float det = dot(e1, p);
                if (abs(det) < 1e-20) continue;
                float invDet = 1.0 / det;
                vec3 s = o - v0;
                // Barycentric bounds widened by kEdge: a ray through the edge two triangles share must hit
                // at least one of them whatever the rounding (NVIDIA's GL compiler let the centre ray of a
                // test slip between the two triangles of a quad); hitting both is harmless.
                const float kEdge = 1e-6;
                float u = dot(s, p) * invDet;
                if (u < -kEdge || u > 1.0 + kEdge) continue;
                vec3 q = cross(s, e1);
                float v = dot(d, q) * invDet;
                if (v < -kEdge || u + v > 1.0 + kEdge) continue;
                float t = dot(e2, q) * invDet;
                if (t > tMin && t < hit.t) {
                    if (testAlpha && v1.w != 0.0 && alphaCutOut(i, vec2(u, v))) continue;
                    hit.t = t;
                    hit.triangle = i;
                    hit.bary = vec2(u, v);
                    // Without testAlpha an alpha-tested triangle (v1.w = 1) is only a candidate, for traceRay to test.
                    if (anyHit && (v1.w == 0.0 || testAlpha)) return true;
                }
            }
        }
        if (top == 0u) break;
        node = stack[--top];
    }
    return hit.triangle != 0xFFFFFFFFu;
}

// Nearest hit in (tMin, tMax), or any hit when `anyHit` (shadow rays). Cut-out points of alpha-tested
// triangles are not hits, for every kind of ray. The first traversal leaves the alpha test to its end: inside the
// traversal (per candidate), opaque scenes' path tracing took 1.5 x the CPU time on llvmpipe, which runs a
// lane-varying branch's body masked for all lanes, texture fetch included; here it costs opaque scenes one
// masked fetch per ray. Where that hit is a cut-out point, one more traversal from beyond it tests candidates as
// it meets them, so a ray through n cut-out layers costs two traversals, not n (and stays within a CPU driver's
// loop budget far longer). That traversal sits in a loop of at most one pass, not a branch: CPU drivers skip a
// loop no lane enters, while they would run a branch's body masked.
// Where a CPU driver's loop limit cut the ray short, the invocation is counted (countIfLoopBudgetSpent).
bool traceRay(vec3 o, vec3 d, float tMin, float tMax, bool anyHit, out Hit hit) {
    bool found = traverseBvh(o, d, tMin, tMax, anyHit, false, hit);
    bool cutOut = found && triangles[3u * hit.triangle + 1u].w != 0.0 && alphaCutOut(hit.triangle, hit.bary);
    for (uint pass = 0u; pass < (cutOut ? 1u : 0u); ++pass) found = traverseBvh(o, d, hit.t, tMax, anyHit, true, hit);
    countIfLoopBudgetSpent();
    return found;
}

// Base colour at a hit: the material's factor, times its texture where it has one.
vec3 surfaceAlbedo(uint material, uint tri, vec2 bary) {
    vec3 albedo = materials[4u * material].rgb;
    float layer = materials[4u * material + 2u].x;
    if (layer >= 0.0) albedo *= textureLod(baseColorTextures, vec3(hitUv(tri, bary), layer), 0.0).rgb;
    return albedo;
}

// The shading normal at a hit (interpolated vertex normals where the mesh has them), on the side of
// `facing` (the geometric normal turned towards the incoming ray).
vec3 shadingNormal(uint tri, vec2 bary, vec3 facing) {
    vec3 n0 = triangleNormals[3u * tri].xyz;
    if (n0 == vec3(0.0)) return facing;
    vec3 n = n0 * (1.0 - bary.x - bary.y) + triangleNormals[3u * tri + 1u].xyz * bary.x + triangleNormals[3u * tri + 2u].xyz * bary.y;
    float len = length(n);
    if (len < 1e-6) return facing;
    n /= len;
    return dot(n, facing) < 0.0 ? -n : n;
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

// A surface's material at a hit: base colour (factor x texture), roughness, metalness and the dielectric
// reflectance at normal incidence (0.04 for metallic-roughness materials, 0 for plain Lambertian ones).
struct Surface {
    vec3 baseColor;
    float roughness;
    float metalness;
    float dielectricF0;
};

Surface surfaceAt(uint material, uint tri, vec2 bary) {
    Surface s;
    s.baseColor = surfaceAlbedo(material, tri, bary);
    s.roughness = materials[4u * material].w;
    s.metalness = materials[4u * material + 1u].w;
    s.dielectricF0 = materials[4u * material + 2u].y;
    return s;
}

// Schlick's (1 − cos)⁵. The cosine comes from a dot product of unit vectors, which rounding takes a little above 1
// for directions within about 3e-4 rad of each other (about one bounce in ten million): pow() of the negative base
// is NaN (GLSL leaves it undefined), and one such sample poisoned its pixel's whole mean. Clamped, and a product.
float schlickWeight(float cosine) {
    float m = clamp(1.0 - cosine, 0.0, 1.0);
    float m2 = m * m;
    return m2 * m2 * m;
}

vec3 specularF0(Surface s) { return mix(vec3(s.dielectricF0), s.baseColor, s.metalness); }
bool hasSpecular(Surface s) { return any(greaterThan(specularF0(s), vec3(0.0))); }
float ggxAlpha(Surface s) { return max(s.roughness * s.roughness, 1e-3); }

// The BRDF (without the cosine): Lambertian diffuse (1 - metalness) * base / pi, and where the surface has
// a specular reflectance, a GGX lobe (height-correlated Smith visibility, Schlick Fresnel) over it. With
// F0 = 0 it is exactly Lambertian.
vec3 evalBrdf(Surface s, vec3 n, vec3 v, vec3 l) {
    float nl = dot(n, l), nv = dot(n, v);
    if (nl <= 0.0 || nv <= 0.0) return vec3(0.0);
    vec3 diffuse = (1.0 - s.metalness) * s.baseColor / PI;
    if (!hasSpecular(s)) return diffuse;
    vec3 h = normalize(v + l);
    float nh = max(dot(n, h), 0.0), vh = max(dot(v, h), 0.0);
    float a2 = ggxAlpha(s) * ggxAlpha(s);
    float d = nh * nh * (a2 - 1.0) + 1.0;
    float D = a2 / (PI * d * d);
    float V = 0.5 / (nl * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nl * nl * (1.0 - a2) + a2));
    vec3 f0 = specularF0(s);
    vec3 F = f0 + (1.0 - f0) * schlickWeight(vh);
    // The diffuse part gets what the coat transmits on the way in and out (Schlick at both angles),
    // which keeps diffuse + specular at or below 1 (the white furnace test).
    vec3 inOut = (1.0 - (f0 + (1.0 - f0) * schlickWeight(nl))) * (1.0 - (f0 + (1.0 - f0) * schlickWeight(nv)));
    return diffuse * inOut + D * V * F;
}

// The probability of sampling the specular lobe (0 for Lambertian surfaces).
float specularProbability(Surface s) { return hasSpecular(s) ? mix(0.25, 1.0, s.metalness) : 0.0; }

float brdfPdf(Surface s, vec3 n, vec3 v, vec3 l) {
    float nl = dot(n, l);
    if (nl <= 0.0) return 0.0;
    float ps = specularProbability(s);
    float pdf = (1.0 - ps) * nl / PI;
    if (ps > 0.0) {
        vec3 h = normalize(v + l);
        float nh = max(dot(n, h), 0.0), vh = max(dot(v, h), 1e-6);
        float a2 = ggxAlpha(s) * ggxAlpha(s);
        float d = nh * nh * (a2 - 1.0) + 1.0;
        pdf += ps * (a2 / (PI * d * d)) * nh / (4.0 * vh);
    }
    return pdf;
}

// Samples a direction from the BRDF (cosine lobe or GGX normal distribution); returns false when the
// sample points below the surface. weight = brdf * cos / pdf.
bool sampleBrdf(Surface s, vec3 n, vec3 v, out vec3 l, out vec3 weight) {
    float ps = specularProbability(s);
    if (ps > 0.0 && rand() < ps) {  // (Lambertian surfaces draw no lobe choice)
        float a2 = ggxAlpha(s) * ggxAlpha(s);
        float u1 = rand(), u2 = rand();
        float cosTheta = sqrt((1.0 - u2) / (1.0 + (a2 - 1.0) * u2)), sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
        float phi = 2.0 * PI * u1;
        vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0, 1, 0)) : cross(n, vec3(1, 0, 0)));
        vec3 b = cross(n, t);
        vec3 h = normalize(t * (cos(phi) * sinTheta) + b * (sin(phi) * sinTheta) + n * cosTheta);
        l = reflect(-v, h);
    } else {
        l = cosineDirection(n);
    }
    float pdf = brdfPdf(s, n, v, l);
    if (!(pdf > 0.0)) return false;  // NaN too
    weight = evalBrdf(s, n, v, l) * max(dot(n, l), 0.0) / pdf;
    return true;
}

// Glass (TriangleMesh::transmission, ior): a clear dielectric interface with GGX microfacets, smooth below this
// roughness (a mirror and a perfect refraction).
const float kSmoothGlass = 0.02;
float glassTransmission(uint material) { return materials[4u * material + 2u].z; }
float glassIor(uint material) { return materials[4u * material + 2u].w; }

// Fresnel reflectance of a dielectric interface, exact (unpolarized): `cosI` the cosine of incidence on the
// incident side, `eta` = η_transmitted / η_incident. 1 under total internal reflection.
float fresnelDielectric(float cosI, float eta) {
    float sin2T = (1.0 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0) return 1.0;
    float cosT = sqrt(1.0 - sin2T);
    float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5 * (rs * rs + rp * rp);
}

// Smith's masking for GGX (Walter et al. 2007, eq. 34): 0 where w sees the microfacet m from behind.
float ggxG1(vec3 w, vec3 m, vec3 n, float a2) {
    float wn = dot(w, n);
    if (dot(w, m) * wn <= 0.0) return 0.0;
    float c2 = wn * wn;
    return 2.0 / (1.0 + sqrt(1.0 + a2 * (1.0 - c2) / c2));
}

// Samples the glass at a hit: a microfacet normal m from D(m)·(m·n) (the shading normal itself when smooth),
// then reflection with probability F(v·m) (exact Fresnel) or refraction otherwise (Walter et al. 2007). The
// Fresnel choice cancels F and 1 − F, so weight = BSDF · |cos| / pdf = |v·m| G1(v) G1(l) / (|v·n| |m·n|) (their
// eq. 41): exactly 1 when smooth, and on average at most 1 when rough (single scattering loses a little, gains
// nothing — the white furnace test). The radiance scaling η² across the interface is left out: it cancels on a
// path that enters and leaves a closed object, and no light source sits inside glass. `n` is the shading normal
// and `ng` the geometric one, both on v's side; `entering`: v is outside (the ray met the front face). False when
// the sample leaves on the wrong side of the geometric surface (shading normals at grazing angles) or v sees a
// microfacet from behind: the path ends there.
bool sampleGlass(vec3 n, vec3 ng, vec3 v, bool entering, float roughness, float ior, out vec3 l, out float weight) {
    float eta = entering ? ior : 1.0 / ior;
    vec3 m = n;
    float a2 = 0.0;
    bool rough = roughness >= kSmoothGlass;
    if (rough) {
        float alpha = max(roughness * roughness, 1e-3);
        a2 = alpha * alpha;
        float u1 = rand(), u2 = rand();
        float cosTheta = sqrt((1.0 - u2) / (1.0 + (a2 - 1.0) * u2)), sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
        float phi = 2.0 * PI * u1;
        vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0, 1, 0)) : cross(n, vec3(1, 0, 0)));
        m = normalize(t * (cos(phi) * sinTheta) + cross(n, t) * (sin(phi) * sinTheta) + n * cosTheta);
    }
    float vm = dot(v, m), vn = dot(v, n);
    weight = 0.0;
    if (vm <= 0.0 || vn <= 0.0) return false;
    bool reflected = rand() < fresnelDielectric(vm, eta);
    l = refract(-v, m, 1.0 / eta);
    // refract() may find total internal reflection a rounding before fresnelDielectric does: reflect then.
    reflected = reflected || dot(l, l) == 0.0;
    l = reflected ? reflect(-v, m) : l;
    // Reflection stays on v's side of the surface, refraction crosses it (of both normals).
    float side = reflected ? 1.0 : -1.0;
    if (side * dot(l, ng) <= 0.0 || side * dot(l, n) <= 0.0) return false;
    weight = rough ? vm * ggxG1(v, m, n, a2) * ggxG1(l, m, n, a2) / (vn * dot(m, n)) : 1.0;
    return true;
}

// Light reflected towards v by the surface at p (normal n) straight from the emitters (one sample,
// chosen by weight = area x luminance), the point and spot lights and the sun.
vec3 directLight(vec3 p, vec3 n, vec3 v, Surface surface, float eps) {
    vec3 sum = vec3(0.0);
    if (sceneLight.counts.x > 0u) {
        float u = rand() * sceneLight.lightWeight.x;
        uint lo = 0u, hi = sceneLight.counts.x - 1u;
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
                vec3 emission = materials[4u * material + 1u].rgb;
                // pdf = (weight / total) / area
                sum += evalBrdf(surface, n, v, l) * emission * cosP * cosL / dist2 * light.y * sceneLight.lightWeight.x / light.w;
            }
        }
    }
    // Point and spot lights (delta lights: every one, every time).
    for (uint i = 0u; i < sceneLight.counts.w; ++i) {
        vec4 a = pointLights[3u * i], intensity = pointLights[3u * i + 1u], c = pointLights[3u * i + 2u];
        vec3 toLight = a.xyz - p;
        float dist2 = dot(toLight, toLight);
        vec3 l = toLight * inversesqrt(dist2);
        float cosP = dot(n, l);
        if (cosP <= 0.0) continue;
        float cone = a.w > -1.0 ? smoothstep(a.w, c.w, dot(-l, c.xyz)) : 1.0;
        if (cone <= 0.0) continue;
        Hit h;
        if (!traceRay(p, l, eps, sqrt(dist2) * (1.0 - 1e-4), true, h)) sum += evalBrdf(surface, n, v, l) * intensity.rgb * cone * cosP / dist2;
    }
    // The sun: a direction drawn uniformly over its disc (a point sun: its centre). The draw hashes the stream's state
    // without advancing it, so the other estimates draw the same numbers whatever the sun's size.
    uint sunRng = pcg(rngState ^ 0x6A09E667u);
    float r = sceneLight.sunDirection.w * sqrt(float(sunRng >> 8) * (1.0 / 16777216.0));
    float phi = 6.28318530718 * float(pcg(sunRng) >> 8) * (1.0 / 16777216.0);
    vec3 sunAxis = sceneLight.sunDirection.xyz;
    vec3 sunT = normalize(cross(sunAxis, abs(sunAxis.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 sunL = normalize(sunAxis + r * (cos(phi) * sunT + sin(phi) * cross(sunAxis, sunT)));
    float cosS = dot(n, sunL);
    if (cosS > 0.0 && any(greaterThan(sceneLight.sunIrradiance.rgb, vec3(0.0)))) {
        Hit h;
        if (!traceRay(p, sunL, eps, 1e30, true, h))
            sum += evalBrdf(surface, n, v, sunL) * sceneLight.sunIrradiance.rgb * cosS;
    }
    return sum;
}

#endif
