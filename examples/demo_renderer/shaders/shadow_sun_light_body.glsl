// The sun's light with its visibility from cascaded shadow maps (--shadows shadowmap: shadow_sun_light.comp) or
// from the shadow classifier's mask (--shadows hybrid: shadow_sun_light_hybrid.comp, SUN_VISIBILITY_FROM_MASK),
// added to the direct lighting that direct_light.comp wrote without the sun (emitters, point lights and the sky keep
// their ray-traced estimator there). w = the sun's visibility (0 where the surface faces away from the sun, 1 on
// the sky).
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    vec4 eye;
    uvec4 size;  // xy image size
} params;
BL_TEXTURE(0) uniform sampler2D gAlbedo;
BL_TEXTURE(1) uniform sampler2D gNormal;
BL_TEXTURE(2) uniform sampler2D gEmission;
BL_TEXTURE(3) uniform sampler2D gPosition;  // w = 1 where geometry was drawn
BL_STORAGE_BUFFER(0) Output { vec4 radiance[]; };
#include "scene_trace.glsl"
#include "shadow_sun.glsl"
#ifdef SUN_VISIBILITY_FROM_MASK
BL_TEXTURE(6) uniform sampler2D sunMask;  // R16F: 1 lit (shadows::ShadowClassifier::resolve)
#endif

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    uint index = pixel.y * params.size.x + pixel.x;
    vec4 position = texelFetch(gPosition, ivec2(pixel), 0);
    if (position.w == 0.0) return;  // the sky: direct_light.comp wrote w = 1
    vec3 p = position.xyz;
    vec4 normal = texelFetch(gNormal, ivec2(pixel), 0);
    vec4 albedo = texelFetch(gAlbedo, ivec2(pixel), 0);
    vec4 emission = texelFetch(gEmission, ivec2(pixel), 0);
    vec3 n = normalize(normal.xyz);
    Surface surface;
    surface.baseColor = albedo.rgb;
    surface.roughness = albedo.a;
    surface.metalness = emission.a;
    surface.dielectricF0 = normal.w;
    vec3 v = normalize(params.eye.xyz - p);
    vec3 l = shadowSun.direction.xyz;
    float cosSun = dot(n, l);
    float visibility = 0.0;
    vec3 sun = vec3(0.0);
    if (cosSun > 0.0) {
#ifdef SUN_VISIBILITY_FROM_MASK
        visibility = texelFetch(sunMask, ivec2(pixel), 0).r;
        // −1: neither the classification nor a sure ray decided the pixel; the maps' own filtered answer.
        if (visibility < 0.0) visibility = sunShadowVisibility(p, n, params.eye.xyz);
#else
        visibility = sunShadowVisibility(p, n, params.eye.xyz);
#endif
        sun = evalBrdf(surface, n, v, l) * shadowSun.irradiance.rgb * cosSun * visibility;
    }
    radiance[index] = vec4(radiance[index].rgb + sun, visibility);
}
