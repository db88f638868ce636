#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 6: one screen probe per 8×8 tile, on a pixel picked by a Hammersley jitter that moves every frame;
// up to 8 attempts to find a pixel that is not sky. Writes the tile's probe info (pixel, depth, normal).
layout(local_size_x = 8, local_size_y = 8) in;
BL_TEXTURE(0) uniform sampler2D depthNow;
BL_TEXTURE(1) uniform usampler2D surfaceNow;
BL_STORAGE_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };

void main() {
    uvec2 tile = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(tile, giFrame.tiles.xy))) return;
    uvec4 info = uvec4(0u);
    uint offset = giPcg(giFrameIndex() * 31u + tile.x * 131u + tile.y * 977u);
    for (uint attempt = 0u; attempt < 8u; ++attempt) {
        vec2 jitter = giHammersley((offset + attempt) & 15u, 16u);
        jitter.x = fract(jitter.x + float(offset >> 8 & 255u) / 256.0);
        uvec2 pixel = tile * 8u + min(uvec2(jitter * 8.0), uvec2(7u));
        if (any(greaterThanEqual(pixel, giFrame.size.xy))) continue;
        float depth = texelFetch(depthNow, ivec2(pixel), 0).r;
        if (giIsSky(depth)) continue;
        vec3 n = giSurfaceNormal(texelFetch(surfaceNow, ivec2(pixel), 0).r);
        vec3 p = giWorldPosition(giPixelUv(pixel), depth, giCamera.inverseViewProjection);
        if (dot(n, giFrame.camera.xyz - p) < 0.0) n = -n;  // the side the camera sees
        info = uvec4(pixel.x | (pixel.y << 16), floatBitsToUint(depth), packSnorm2x16(giOctEncode(n)), GI_PROBE_VALID);
        break;
    }
    probeInfo[tile.y * giFrame.tiles.x + tile.x] = info;
}
