// The environment map (cube or equirectangular) seen along a direction, times its intensity; black when
// the frame has none. Both samplers are always bound (the context binds a black 1×1 for the unused one).
#ifndef BRICKLIGHT_GI_ENVIRONMENT_GLSL
#define BRICKLIGHT_GI_ENVIRONMENT_GLSL

BL_TEXTURE(13) uniform samplerCube environmentCube;
BL_TEXTURE(14) uniform sampler2D environmentEquirect;

// Equirectangular: u = atan2(d.z, d.x) / 2π + 0.5, v = acos(d.y) / π (v = 0 at +y, the top row).
vec3 giEnvironment(vec3 d) {
    vec3 c = vec3(0.0);
    if (giFrame.inputs.z == GI_ENV_CUBE) {
        c = textureLod(environmentCube, d, 0.0).rgb;
    } else if (giFrame.inputs.z == GI_ENV_EQUIRECT) {
        vec2 uv = vec2(atan(d.z, d.x) / (2.0 * GI_PI) + 0.5, acos(clamp(d.y, -1.0, 1.0)) / GI_PI);
        c = textureLod(environmentEquirect, uv, 0.0).rgb;
    }
    c *= giFrame.normalOffset.w;
    return giFinite(c) ? max(c, vec3(0.0)) : vec3(0.0);
}

// What a ray traced for the screen's pixels (a probe's, a specular or a reflection ray) brings where it leaves the
// scene: the environment, or nothing where the application's direct lighting already lit the pixels with it
// (DispatchDesc::environmentInDirectLight; it would count twice). Surfaces GI lights itself (re-lit texels, unseen
// hits' paths) take giEnvironment: they stand in for the screen's light, which holds it.
vec3 giMissRadiance(vec3 d) {
    return (giFrame.relight.y & GI_RELIGHT_ENVIRONMENT_IN_DIRECT) != 0u ? vec3(0.0) : giEnvironment(d);
}

#endif
