#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
// The fast path's final image: direct light + GI, composited like image-based lighting (design §5):
//   combined = direct + (1 - metalness) · base · diffuseGI + specularGI · (F0 · A + B)
// with (A, B) the split-sum scale and bias of our GGX lobe (specular_albedo.h: integrated, not fitted). Surfaces with F0 = 0
// are exactly Lambertian in our BRDF and get no specular term. Also writes the "lit" image that GI
// injects next frame: what surfaces send back into the scene, i.e. the combined radiance without the
// emitters' own emission (direct lighting already samples the emitters; counting their emission again
// through GI would count it twice). Glass pixels (alpha 1 in the glass pass's target: render/glass.frag) take
// the glass's radiance in the combined image; the lit image keeps the opaque surface behind the glass, which is
// what the G-buffer that GI reads holds there. With hybrid reflections (reflections::ReflectionClassifier, docs/render.md)
// their denoised result replaces the GI's specular by its weight; their screen-space rays read the lit image of the
// previous frame, without the emitters' emission for the same reason as GI (the direct light samples the emitters
// through the full BRDF, specular lobe included).
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    vec4 eye;     // xyz
    uvec4 size;   // xy image size, z: 1 = GI on, w: 1 = the lit image holds GI (0: direct only, one bounce)
} params;
BL_TEXTURE(0) uniform sampler2D gAlbedo;    // rgb base colour, a roughness
BL_TEXTURE(1) uniform sampler2D gNormal;    // xyz normal, w dielectric F0
BL_TEXTURE(2) uniform sampler2D gEmission;  // rgb emission, a metalness
BL_TEXTURE(3) uniform sampler2D gPosition;  // xyz, w = 1 where geometry was drawn
BL_TEXTURE(4) uniform sampler2D diffuseGI;
BL_TEXTURE(5) uniform sampler2D specularGI;
BL_TEXTURE(6) uniform sampler2D glassRadiance;  // 1×1 and transparent while no glass is drawn
BL_TEXTURE(7) uniform sampler2D reflections;    // rgb, a = weight over the GI's specular; 1×1 and transparent when off
BL_TEXTURE(8) uniform sampler2D specularAlbedo;  // rg: the split sum's (A, B) at (n·v, roughness), specular_albedo.h
BL_READ_BUFFER(0) Direct { vec4 direct[]; };
BL_STORAGE_BUFFER(0) Combined { vec4 combined[]; };
BL_IMAGE(0, rgba16f) uniform writeonly image2D lit;

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    uint index = pixel.y * params.size.x + pixel.x;
    vec3 radiance = direct[index].rgb;
    vec3 sent = radiance;  // what the lit image holds: radiance with GI when fed back
    vec3 emission = vec3(0.0);
    vec4 position = texelFetch(gPosition, ivec2(pixel), 0);
    bool geometry = position.w != 0.0;
    bool giOn = params.size.z != 0u;
    // GI's flag only in a condition with per-pixel data: lavapipe compiles (and leaks) a new variant per dispatch for branches on constants only (docs/notes/soak.md).
    if (geometry && giOn) {
        vec4 albedo = texelFetch(gAlbedo, ivec2(pixel), 0);
        vec4 normal = texelFetch(gNormal, ivec2(pixel), 0);
        vec4 em = texelFetch(gEmission, ivec2(pixel), 0);
        emission = em.rgb;
        float metalness = em.a;
        vec3 f0 = mix(vec3(normal.w), albedo.rgb, metalness);
        vec3 n = normalize(normal.xyz);
        float nDotV = clamp(dot(n, normalize(params.eye.xyz - position.xyz)), 1e-4, 1.0);
        vec3 gi = (1.0 - metalness) * albedo.rgb * texelFetch(diffuseGI, ivec2(pixel), 0).rgb;
        if (any(greaterThan(f0, vec3(0.0)))) {
            vec2 ab = textureLod(specularAlbedo, vec2(nDotV, albedo.a), 0.0).rg;
            vec3 specular = texelFetch(specularGI, ivec2(pixel), 0).rgb;
            vec4 reflection = texelFetch(reflections, min(ivec2(pixel), textureSize(reflections, 0) - 1), 0);
            specular = mix(specular, reflection.rgb, clamp(reflection.a, 0.0, 1.0));
            gi += specular * (f0 * ab.x + ab.y);
        }
        radiance += gi;
        sent = params.size.w != 0u ? radiance : sent;  // a select, not a branch on a constant
    } else if (geometry) {
        emission = texelFetch(gEmission, ivec2(pixel), 0).rgb;  // GI off: direct light only
    }
    vec4 glass = texelFetch(glassRadiance, min(ivec2(pixel), textureSize(glassRadiance, 0) - 1), 0);
    combined[index] = vec4(glass.a > 0.0 ? glass.rgb : radiance, 1.0);
    imageStore(lit, ivec2(pixel), vec4(max(sent - emission, vec3(0.0)), 1.0));

}
