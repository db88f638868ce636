#version 450
#extension GL_GOOGLE_include_directive : require
// The clip-map seen from a camera (vct::Clipmap::debugView): each pixel marches its ray through the traced
// volumes voxel by voxel (nearest, no filtering) of one level — or of the finest level that holds the point —
// and shows the first voxel at least a quarter opaque: its opacity along x, y, z as rgb; the light it sends
// back along the ray (or towards one chosen direction), tone-mapped; its level; or whether this update
// rewrote it (red) or kept it (grey). Nothing hit: black.
#include "bricklight/bindings.glsl"
#include "bricklight/cone_trace.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
BL_CONSTANTS(0) uniform Params {
    mat4 inverseViewProjection;
    vec4 eye;     // xyz, w: exposure
    uvec4 size;   // xy output size, z mode (0 opacity, 1 emittance, 2 level, 3 rewritten), w level (0xFFFFFFFF: finest holding)
    ivec4 face;   // x: the emittance direction (−1: back along the ray)
} params;
BL_IMAGE(0, rgba8) uniform writeonly image2D outputImage;

vec3 levelColour(uint level) {
    const vec3 colours[8] = vec3[8](vec3(0.9, 0.2, 0.2), vec3(0.9, 0.6, 0.1), vec3(0.9, 0.9, 0.2), vec3(0.3, 0.9, 0.3),
                                    vec3(0.2, 0.8, 0.9), vec3(0.3, 0.4, 0.95), vec3(0.7, 0.3, 0.9), vec3(0.9, 0.9, 0.9));
    return colours[min(level, 7u)];
}

// Direction d's radiance at an opacity-region texel (the regions lie side by side in x; one when isotropic).
vec4 faceTexel(uint d, ivec3 t) {
    if (blVctFrame.params.z == 0u) return vec4(0.0);  // no emittance
    int r = int(blVctFrame.params.x);
    uint region = blVctFrame.params.z == 6u ? 1u + d : 1u;
    return texelFetch(blVctEmittanceVolume, t + ivec3(vctRegionX(region, uint(r)), 0, 0), 0);
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, params.size.xy))) return;
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(params.size.xy) * 2.0 - 1.0;
    vec4 far = params.inverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - params.eye.xyz);
    float finest = blVctFrame.scales.x;
    float resolution = float(blVctFrame.params.x);
    uint levels = blVctFrame.params.y, mips = blVctFrame.flags.y;
    vec3 p = params.eye.xyz / finest;  // finest-voxel units
    vec3 invDir = 1.0 / mix(dir, vec3(1.0e-12), lessThan(abs(dir), vec3(1.0e-12)));
    vec3 colour = vec3(0.0);
    // The mode and face with per-invocation data added (zero here): lavapipe compiles a variant per dispatch for
    // branches on constants alone (docs/notes/soak.md), and the viewer draws a debug view every frame.
    uint onScreen = pixel.x < params.size.x ? 0u : 1u;
    uint mode = params.size.z + onScreen;
    int face = params.face.x + int(onScreen);
    for (int i = 0; i < 1024; ++i) {
        uint level = params.size.w != 0xFFFFFFFFu ? params.size.w : blVctHoldingLevel(0u, p, 0.0, levels, resolution);
        if (params.size.w == 0xFFFFFFFFu && level >= levels) level = levels + mips;  // no level holds the point
        if (level >= levels + mips) {
            // Outside every level: step towards the clip-map by the coarsest voxel.
            p += dir * float(1u << (levels - 1u));
            continue;
        }
        float scale = float(1u << level);
        ivec3 voxel = ivec3(floor(p / scale));
        // A level's voxels, toroidally; a mip's (a chosen level past the last), in its box with the border.
        uint mip = level >= levels ? level - (levels - 1u) : 0u;
        ivec3 lo = mip == 0u ? blVctFrame.origin[level].xyz : (blVctFrame.origin[levels - 1u].xyz >> int(mip)) - 1;
        int extent = mip == 0u ? int(resolution) : (int(resolution) >> mip) + 3;
        if (any(lessThan(voxel, lo)) || any(greaterThanEqual(voxel, lo + extent))) {
            p += dir * scale * 0.5;
            continue;
        }
        ivec3 texel = mip == 0u ? vctTexel(0u, level, voxel, uint(resolution))
                                : vctMipBoxOffset(mip, levels, uint(resolution)) + voxel - lo + ivec3(1, 0, 0);
        vec3 alpha = texelFetch(blVctOpacityVolume, texel, 0).rgb;
        if (max(alpha.x, max(alpha.y, alpha.z)) >= 0.25) {
            if (mode == 0u) {
                colour = alpha;
            } else if (mode == 1u) {
                vec3 e = vec3(0.0);
                if (face >= 0) e = faceTexel(uint(face), texel).rgb;
                else {
                    vec3 w = abs(dir);  // the faces that send light back along the ray
                    e = w.x * faceTexel(dir.x > 0.0 ? 3u : 0u, texel).rgb + w.y * faceTexel(dir.y > 0.0 ? 4u : 1u, texel).rgb +
                        w.z * faceTexel(dir.z > 0.0 ? 5u : 2u, texel).rgb;
                }
                colour = e * params.eye.w;
                colour = colour / (1.0 + colour);  // Reinhard, then sRGB-ish
                colour = pow(colour, vec3(1.0 / 2.2));
            } else if (mode == 2u) {
                colour = levelColour(level);
            } else {
                bool rewritten = false;
                for (uint b = 0u; b < blVctFrame.params.w; ++b) {
                    BlVctBox box = blVctFrame.boxes[b];
                    rewritten = rewritten || (uint(box.minLevel.w) == level && all(greaterThanEqual(voxel, box.minLevel.xyz)) &&
                                              all(lessThan(voxel, box.max.xyz)));
                }
                colour = rewritten ? vec3(0.9, 0.15, 0.1) : vec3(0.5);
            }
            break;
        }
        // To the voxel's far side along the ray (a DDA step), then a hair beyond.
        vec3 cellLo = vec3(voxel) * scale, cellHi = cellLo + scale;
        vec3 tExit = max((cellLo - p) * invDir, (cellHi - p) * invDir);
        float step = min(tExit.x, min(tExit.y, tExit.z));
        p += dir * (max(step, 0.0) + 1.0e-3 * scale);
    }
    imageStore(outputImage, ivec2(pixel), vec4(clamp(colour, 0.0, 1.0), 1.0));
}
