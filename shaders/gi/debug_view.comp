#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_sh.glsl"
// Debug views of the latest dispatch, at display size (tone-mapped x / (1 + x) after exposure):
//   0 radiance cache    primary rays through the field, the radiance cache at the hit
//   1 irradiance cache  primary rays, the hit brick's SH for the hit normal (irradiance / π)
//   2 probes            the screen probes' 8×8 texels, each probe stretched over its own tile
//   3 probe SH          the pixel's probe SH for the pixel's normal
//   4 disocclusion      white = history kept
//   5 sample count      the diffuse history's length (white = the cap)
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(2) uniform Pass { uvec4 mode; vec4 exposure; } pass;
BL_TEXTURE(0) uniform sampler2D depthNow;
BL_TEXTURE(1) uniform usampler2D surfaceNow;
BL_TEXTURE(2) uniform sampler2D probes;
BL_TEXTURE(3) uniform sampler2D disocclusion;
BL_TEXTURE(4) uniform sampler2D diffuseHistory;
BL_READ_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
BL_READ_BUFFER(1) ProbeSH { vec4 probeSH[]; };
BL_READ_BUFFER(2) BrickSH { uvec2 giBrickSH[]; };
BL_IMAGE(0, rgba8) uniform writeonly image2D outputImage;
BL_IMAGE(1, r32ui) uniform readonly uimage3D giRadianceCache;
#define GI_USES_RADIANCE_CACHE
#define GI_USES_BRICK_SH
#include "gi_bricks.glsl"

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, giFrame.size.zw))) return;
    vec2 uv = (vec2(pixel) + 0.5) / vec2(giFrame.size.zw);
    uvec2 internalPixel = min(uvec2(uv * vec2(giFrame.size.xy)), giFrame.size.xy - 1u);
    vec3 colour = vec3(0.0);
    uint mode = pass.mode.x;
    if (mode <= 1u) {
        // A point halfway in depth: finite also for infinite (reversed-Z) projections.
        vec3 d = normalize(giWorldPosition(uv, 0.5, giCamera.inverseViewProjection) - giFrame.camera.xyz);
        BlSdfRay ray = blSdfMakeRay(giFrame.camera.xyz, d, giFrame.trace.z, giFrame.trace.w);
        ray.startCascade = giFrame.cascades.x;
        ray.endCascade = giFrame.cascades.y;
        BlSdfHit hit = blSdfTrace(ray);
        if (hit.hit) {
            if (mode == 0u) {
                vec3 radiance;
                if (giRadianceAt(ray.origin + d * hit.t, hit.brickId, hit.brickUvw, hit.cascade, radiance)) colour = radiance;
                else colour = vec3(0.3, 0.0, 0.3) / pass.exposure.x;  // no data: magenta
            } else {
                float w;
                GiSH s = giLoadBrickSH(hit.brickId, w);
                colour = w > 0.0 ? giShDiffuse(s, hit.normal) : vec3(0.3, 0.0, 0.3) / pass.exposure.x;
            }
        }
    } else if (mode == 2u) {
        uvec2 tile = min(internalPixel / giProbeTile(), giFrame.tiles.xy - 1u);
        uvec2 local = min((internalPixel - tile * giProbeTile()) * 8u / giProbeTile(), uvec2(7u));
        colour = texelFetch(probes, ivec2(tile * 8u + local), 0).rgb;
    } else if (mode == 3u) {
        uvec2 tile = min(internalPixel / giProbeTile(), giFrame.tiles.xy - 1u);
        uint index = tile.y * giFrame.tiles.x + tile.x;
        if ((probeInfo[index].w & GI_PROBE_VALID) != 0u && !giIsSky(texelFetch(depthNow, ivec2(internalPixel), 0).r)) {
            GiSH s;
            for (int i = 0; i < 9; ++i) s.c[i] = probeSH[index * 9u + uint(i)].rgb;
            colour = giShDiffuse(s, giSurfaceNormal(texelFetch(surfaceNow, ivec2(internalPixel), 0).r));
        }
    } else if (mode == 4u) {
        colour = vec3(texelFetch(disocclusion, ivec2(internalPixel), 0).r) / pass.exposure.x;
    } else {
        colour = vec3(texelFetch(diffuseHistory, ivec2(internalPixel), 0).a / float(giFrame.inputs.w)) / pass.exposure.x;
    }
    colour *= pass.exposure.x;
    // Masks and counts are shown as they are; light is tone-mapped.
    imageStore(outputImage, ivec2(pixel), vec4(mode >= 4u ? clamp(colour, 0.0, 1.0) : colour / (1.0 + colour), 1.0));
}
