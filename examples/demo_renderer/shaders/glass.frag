#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// Glossy glass through the voxel clip-map: the example custom material of the public cone-trace API
// (bricklight/cone_trace.glsl; docs/vct.md). The renderer draws the glass meshes with render/gbuffer.vert after the
// clip-map is built without them (raster_renderer_glass.cpp) and binds Clipmap::traceBindings() (textures 8 and 9,
// read buffer 7) with its scene (read buffers 0..6, scene_trace.glsl).
//
// Per pixel, the nearest glass surface: Fresnel (exact, dielectric) × the light along the mirror direction +
// (1 − Fresnel) × the light along the refracted one. Each of the two follows a ray through the glass interfaces it
// meets — refracting where it enters and leaves (Snell's law with each hit's interpolated normal), reflecting
// under total internal reflection — so a sphere acts as the thick lens it is and shows the room upside down.
// Where the ray leaves the last interface, one cone (blTraceCone) gathers the light; the clip-map holds no glass,
// so cones cross other glass unhindered. What the clip-map does not hold is added along the ray's axis: the
// emission of an emitter it meets (the voxels hold the light surfaces reflect, not the emitters' own), and the sky
// where it meets nothing (× the cone's transmittance). The cone's width comes from the roughness as the specular
// tracer's (VXGI 1.0: coneFactor = roughness² · √π, at least 0.01) for a reflection; a rough refraction turns
// a microfacet's tilt δ into a deviation of δ·|1 − η_i/η_t| instead of 2δ, so it widens the cone by that share,
// the interfaces' spreads adding in quadrature. The path tracer's glass (sampleGlass) is the reference.
// A partly transmissive surface (transmission < 1) mixes in its opaque material: direct light by next-event
// estimation (scene_trace.glsl's directLight) and diffuse light from four cones.
BL_CONSTANTS(0) uniform Camera {  // render/gbuffer.vert's
    mat4 viewProjection;
    mat4 previousViewProjection;
    vec4 eye;
} camera;
BL_CONSTANTS(2) uniform GlassParams {
    uvec4 params;  // x frame (random numbers)
} glass;
BL_TEXTURE(0) uniform sampler2D gPosition;  // the G-buffer's world position, w = 1 where an opaque surface was drawn
#include "scene_trace.glsl"
#include "bricklight/cone_trace.glsl"

layout(location = 0) in vec3 vNormal;
layout(location = 1) flat in uint vMaterial;
layout(location = 2) in vec4 vClip;
layout(location = 3) in vec4 vPreviousClip;
layout(location = 4) in vec3 vWorld;
layout(location = 5) in vec2 vUv;
layout(location = 6) flat in vec3 vGeometricNormal;
layout(location = 0) out vec4 outRadiance;  // rgb radiance towards the camera, a = 1: a glass pixel

const int kMaxInterfaces = 8;  // glass interfaces a ray follows before its cone starts

float reflectionCone(float roughness) { return max(roughness * roughness * 1.7724539, 0.01); }
// The cone a rough interface adds to a refraction (eta = η_t / η_i).
float refractionCone(float roughness, float eta) { return reflectionCone(roughness) * abs(1.0 - 1.0 / eta) * 0.5; }

// Light arriving at `origin` along −d, the ray starting with cone spread² `spread2`.
vec3 lightAlong(vec3 origin, vec3 d, float spread2) {
    float eps = sceneLight.lightWeight.y;
    vec3 emitted = vec3(0.0);
    bool escaped = false;
    float surface = 0.0;  // world distance to the opaque surface the ray meets (0: none)
    for (int i = 0; i <= kMaxInterfaces; ++i) {
        Hit h;
        if (!traceRay(origin, d, eps, 1e30, false, h)) {
            escaped = true;
            break;
        }
        uint material = floatBitsToUint(triangles[3u * h.triangle].w);
        vec3 ng = triangleNormal(h.triangle);
        bool front = dot(ng, d) < 0.0;
        if (glassTransmission(material) <= 0.0 || i == kMaxInterfaces) {  // an opaque surface: the cone sees it
            emitted = front ? materials[4u * material + 1u].rgb : vec3(0.0);
            surface = max(h.t, 1e-6);
            break;
        }
        vec3 n = shadingNormal(h.triangle, h.bary, front ? ng : -ng);
        float ior = glassIor(material);
        float eta = front ? ior : 1.0 / ior;
        vec3 t = refract(d, n, 1.0 / eta);
        float roughness = materials[4u * material].w;
        bool internal = dot(t, t) == 0.0;  // total internal reflection
        float widen = internal ? reflectionCone(roughness) : refractionCone(roughness, eta);
        spread2 += widen * widen;
        vec3 q = origin + d * h.t;
        d = internal ? reflect(d, n) : t;
        origin = q + (dot(d, ng) > 0.0 ? ng : -ng) * eps;  // off the surface on the side the ray goes on
    }
    BlCone cone = blDefaultCone(origin, d, max(sqrt(spread2), 0.01));
    cone.firstSampleT = 0.5;  // no glass voxels to step over: start at the surface
    cone.surfaceDistance = surface;  // the ray's exact hit: the cone's light stops there, none leaks from behind
    BlConeResult r = blTraceCone(cone);
    return r.radiance + emitted + (escaped ? sceneLight.sky.rgb * (1.0 - r.finalOpacity) : vec3(0.0));
}

// The opaque share of a partly transmissive surface: direct light and diffuse light from four cones.
vec3 opaqueShare(uint material, vec3 p, vec3 n, vec3 v) {
    Surface s;
    s.baseColor = materials[4u * material].rgb;
    float layer = materials[4u * material + 2u].x;
    if (layer >= 0.0) s.baseColor *= textureLod(baseColorTextures, vec3(vUv, layer), 0.0).rgb;
    s.roughness = materials[4u * material].w;
    s.metalness = materials[4u * material + 1u].w;
    s.dielectricF0 = materials[4u * material + 2u].y;
    const uint samples = 4u;
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < samples; ++i) sum += directLight(p, n, v, s, sceneLight.lightWeight.y);
    vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0, 1, 0)) : cross(n, vec3(1, 0, 0)));
    vec3 b = cross(n, t);
    vec3 irradiance = vec3(0.0);  // × 1/4: irradiance / π as the mean radiance of four cones of π/2 sr about n
    for (int k = 0; k < 4; ++k) {
        float phi = 1.5707963 * float(k) + 0.7853982;
        vec3 dir = normalize(0.6614 * (cos(phi) * t + sin(phi) * b) + 0.75 * n);
        BlConeResult r = blTraceCone(blDefaultCone(p + n * blVctFrame.scales.x, dir, 1.76));
        irradiance += r.radiance + sceneLight.sky.rgb * (1.0 - r.finalOpacity);
    }
    return sum / float(samples) + (1.0 - s.metalness) * s.baseColor * irradiance * 0.25;
}

void main() {
    vec3 toEye = camera.eye.xyz - vWorld;
    // The G-buffer's depth test, by distance from the eye: glass behind an opaque surface is hidden.
    vec4 opaque = texelFetch(gPosition, ivec2(gl_FragCoord.xy), 0);
    vec3 toOpaque = opaque.xyz - camera.eye.xyz;
    if (opaque.w != 0.0 && dot(toOpaque, toOpaque) < dot(toEye, toEye)) discard;
    vec3 v = normalize(toEye);
    bool front = dot(vGeometricNormal, toEye) > 0.0;  // outside, looking in
    vec3 ng = front ? vGeometricNormal : -vGeometricNormal;
    vec3 n = normalize(vNormal);
    n = dot(n, ng) < 0.0 ? -n : n;
    n = dot(n, v) > 1e-4 ? n : ng;  // an interpolated normal turned away at a silhouette: the facet's own
    uint material = vMaterial;
    float roughness = materials[4u * material].w;
    float ior = glassIor(material);
    float eta = front ? ior : 1.0 / ior;
    float fresnel = fresnelDielectric(dot(n, v), eta);
    // The rasterized position lies on the triangle only up to interpolation: rays start a few ray offsets off it,
    // on the side they leave by (else a refracted ray may meet the surface it starts on).
    float offset = 16.0 * sceneLight.lightWeight.y;
    vec3 radiance = fresnel * lightAlong(vWorld + ng * offset, reflect(-v, n), reflectionCone(roughness) * reflectionCone(roughness));
    vec3 t = refract(-v, n, 1.0 / eta);
    if (fresnel < 1.0 && dot(t, t) > 0.0) {
        float spread = refractionCone(roughness, eta);
        radiance += (1.0 - fresnel) * lightAlong(vWorld - ng * offset, t, spread * spread);
    }
    float transmission = glassTransmission(material);
    if (transmission < 1.0) {
        rngState = pcg(uint(gl_FragCoord.x) ^ pcg(uint(gl_FragCoord.y) ^ pcg(glass.params.x ^ sceneLight.counts.y)));
        radiance = mix(opaqueShare(material, vWorld + ng * sceneLight.lightWeight.y, n, v), radiance, transmission);
    }
    vec3 emission = front ? materials[4u * material + 1u].rgb : vec3(0.0);
    outRadiance = vec4(radiance + emission, 1.0);
}
