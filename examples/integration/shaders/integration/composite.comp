#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The public trace API. It declares the field's bindings (texture slot 15, read buffers 4..7): the record
// that runs this shader merges SdfScene::traceBindings() into its own bindings.
#include "bricklight/trace.glsl"
// The application's composite: direct sunlight with shadows traced through the distance field, plus GI,
// combined like image-based lighting (docs/gi.md, "Integration"):
//   lit = direct + albedo * diffuseGI + specularGI * (F0 * A + B)
// `lit` is the frame's image and, next frame, GI's previousLitOutput: the light surfaces send back into the
// scene, so every frame adds one more bounce.
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    mat4 inverseViewProjection;  // the G-buffer's camera (y-flipped projection, depth [0, 1])
    vec4 eye;                    // xyz
    vec4 sunDirection;           // xyz towards the sun; w: how far shadow rays start off the surface
    vec4 sunIrradiance;          // rgb
    uvec4 size;                  // xy image size
} params;
BL_TEXTURE(0) uniform sampler2D gDepth;
BL_TEXTURE(1) uniform sampler2D gNormal;
BL_TEXTURE(2) uniform sampler2D gAlbedoRoughness;
BL_TEXTURE(3) uniform sampler2D diffuseGI;
BL_TEXTURE(4) uniform sampler2D specularGI;
BL_IMAGE(0, rgba16f) uniform writeonly image2D lit;
BL_IMAGE(1, rgba16f) uniform writeonly image2D direct;  // rgb: direct light alone; a: sun visibility (for the checks)

const float kPi = 3.14159265;
const float kDielectricF0 = 0.04;

// Scale and bias of the split-sum GGX term for (roughness, N.V): the analytic fit from Karis,
// "Physically Based Shading on Mobile" (2014); no lookup texture needed.
vec2 splitSumScaleBias(float roughness, float nDotV) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * nDotV)) * r.x + r.y;
    return vec2(-1.04, 1.04) * a004 + r.zw;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), params.size.xy))) return;
    float depth = texelFetch(gDepth, pixel, 0).r;
    if (depth >= 1.0) {  // nothing drawn: no sky in this scene
        imageStore(lit, pixel, vec4(0.0));
        imageStore(direct, pixel, vec4(0.0));
        return;
    }
    // World position from depth: pixel centre to NDC (row 0 is NDC y = -1 under the y-flipped projection).
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(params.size.xy) * 2.0 - 1.0;
    vec4 world = params.inverseViewProjection * vec4(ndc, depth, 1.0);
    vec3 position = world.xyz / world.w;
    vec3 n = normalize(texelFetch(gNormal, pixel, 0).xyz);
    vec4 albedoRoughness = texelFetch(gAlbedoRoughness, pixel, 0);
    vec3 albedo = albedoRoughness.rgb;
    vec3 l = params.sunDirection.xyz;

    // Sun: Lambert, shadowed by one ray through the distance field. The ray starts a little off the
    // surface so that it does not find the surface it leaves. A ray that gives up (out of steps in the
    // last cascade) found nothing in the way: lit.
    float nDotL = dot(n, l);
    float visibility = 0.0;
    if (nDotL > 0.0) {
        BlSdfRay ray = blSdfMakeRay(position + n * params.sunDirection.w, l, 0.0, 1e30);
        visibility = blSdfTrace(ray).hit ? 0.0 : 1.0;
    }
    vec3 sun = albedo / kPi * params.sunIrradiance.rgb * max(nDotL, 0.0) * visibility;

    // GI: diffuse is radiance for a white Lambertian surface (times albedo); specular is the incoming
    // radiance along the reflection lobe (times the split-sum term).
    float nDotV = clamp(dot(n, normalize(params.eye.xyz - position)), 1e-4, 1.0);
    vec2 ab = splitSumScaleBias(albedoRoughness.a, nDotV);
    vec3 indirect = albedo * texelFetch(diffuseGI, pixel, 0).rgb + texelFetch(specularGI, pixel, 0).rgb * (kDielectricF0 * ab.x + ab.y);

    imageStore(lit, pixel, vec4(sun + indirect, 1.0));
    imageStore(direct, pixel, vec4(sun, visibility));
}
