#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "bricklight/trace.glsl"
#include "gi_common.glsl"
#include "gi_specular.glsl"
#include "gi_alpha.glsl"
// Pass 11: every pixel's own specular ray, marched only through the brick its 4×4 tile's pre-trace hit
// (sphere tracing inside that voxel): a hit reads the radiance cache; the tile's miss means the
// environment. Otherwise alpha 0, and the interpolation pass falls back to the SH irradiance caches.
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D depthNow;
BL_TEXTURE(1) uniform usampler2D surfaceNow;
BL_TEXTURE(2) uniform usampler2D pretrace;
BL_READ_BUFFER(0) BrickOwners { uint brickOwners[]; };
BL_IMAGE(0, rgba16f) uniform writeonly image2D specular;
BL_IMAGE(1, r32ui) uniform readonly uimage3D giRadianceCache;
#include "gi_environment.glsl"
#define GI_USES_RADIANCE_CACHE
#include "gi_bricks.glsl"
#define GI_PRETRACE_MISS 0xFFFFFFFEu
#define GI_PRETRACE_NONE 0xFFFFFFFFu

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, giFrame.size.xy))) return;
    vec4 result = vec4(0.0);
    float depth = texelFetch(depthNow, ivec2(pixel), 0).r;
    uint surface = texelFetch(surfaceNow, ivec2(pixel), 0).r;
    uint brick = texelFetch(pretrace, ivec2(pixel / 4u), 0).r;
    if (!giIsSky(depth) && brick != GI_PRETRACE_NONE && giSurfaceRoughness(surface) <= giFrame.normalScale.w) {
        vec3 p = giWorldPosition(giPixelUv(pixel), depth, giCamera.inverseViewProjection);
        vec3 n = giSurfaceNormal(surface);
        vec3 toEye = normalize(giFrame.camera.xyz - p);
        if (dot(n, toEye) < 0.0) n = -n;
        uint rng = giPcg(giPcg(pixel.y * giFrame.size.x + pixel.x) ^ (giFrameIndex() + 0x9e3779b9u));
        vec3 d = giSpecularDirection(n, toEye, giSurfaceRoughness(surface), vec2(giRandom(rng), giRandom(rng)));
        vec3 o = p + n * giPushOff(p, giFrame.trace.y);
        if (brick == GI_PRETRACE_MISS) {
            result = vec4(giMissRadiance(d), 1.0);
        } else {
            uint cascade;
            ivec3 voxel = giOwnerVoxel(brickOwners[brick], cascade);
            if (giBrickOfVoxel(voxel, cascade) == brick) {
                float size = giVoxelSize(cascade);
                vec3 lo = vec3(voxel) * size, hi = lo + size;
                vec3 invD = 1.0 / mix(d, vec3(1e-20), lessThan(abs(d), vec3(1e-20)));
                vec2 span = blSdfRayBox(o, invD, lo, hi);
                float band = blSdfTable.cascades[cascade].voxelSize.w;
                float eps = blSdfTable.cascades[cascade].voxelSize.z * giFrame.epsilon.y;
                float s = max(span.x, giFrame.trace.z);
                bool alphaTested = (blSdfBrickAabbs[brick] & BL_SDF_AABB_ALPHA_TESTED) != 0u && blAlphaCacheKept();
                for (int i = 0; i < 16 && s <= span.y; ++i) {
                    vec3 uvw = clamp((o + d * s - lo) / size, 0.0, 1.0);
                    float dist = blSdfSampleBrick(brick, uvw) * band;
                    if (dist < eps && alphaTested && blSdfCellAlphaTested(brick, uvw)) {
                        // A card's cut-out part, this time: march on past it (as blSdfContinueRay); leaving the
                        // brick without another hit leaves the pixel to the SH caches.
                        float coverage = blAlphaCacheCoverage(brick, uvw);
                        if (coverage >= 0.0 && giRandom(rng) >= coverage) {
                            s += min(2.5 * eps / max(abs(dot(blSdfBrickNormal(brick, uvw, d), d)), 1e-3), 3.0 * size / 7.0);
                            continue;
                        }
                    }
                    if (dist < eps) {
                        vec3 radiance;
                        if (giRadianceAt(o + d * s, brick, uvw, cascade, radiance)) result = vec4(radiance, 1.0);
                        break;
                    }
                    s += dist;
                }
            }
        }
    }
    imageStore(specular, ivec2(pixel), result);
}
