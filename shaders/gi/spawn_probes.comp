#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 6: one screen probe per tile of giProbeTile()² internal pixels, on a pixel picked by a Hammersley
// jitter that moves every frame; up to 8 attempts to find a pixel that is not sky. Writes the tile's probe
// info (pixel, depth, normal). Tiles are 8×8, or 16×16 from an internal width of 1440 on
// (ContextDesc::probeTile): the probes carry low-frequency irradiance, so at high internal resolutions
// 16×16 keeps about as many probes per screen as 8×8 at 960x540 and cuts the probes' tracing and
// projection, the frame's largest passes there, to a quarter.
layout(local_size_x = 8, local_size_y = 8) in;
// Reads the application's G-buffer (gi_input.glsl), as the downsample stores it: the two run side by side.
BL_TEXTURE(0) uniform sampler2D inputDepth;
BL_TEXTURE(1) uniform sampler2D inputNormals;
BL_TEXTURE(2) uniform sampler2D inputRoughness;
BL_STORAGE_BUFFER(0) ProbeInfo { uvec4 probeInfo[]; };
#include "gi_input.glsl"

void main() {
    uvec2 tile = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(tile, giFrame.tiles.xy))) return;
    uvec4 info = uvec4(0u);
    uint offset = giPcg(giFrameIndex() * 31u + tile.x * 131u + tile.y * 977u);
    for (uint attempt = 0u; attempt < 8u; ++attempt) {
        vec2 jitter = giHammersley((offset + attempt) & 15u, 16u);
        jitter.x = fract(jitter.x + float(offset >> 8 & 255u) / 256.0);
        uvec2 pixel = tile * giProbeTile() + min(uvec2(jitter * float(giProbeTile())), uvec2(giProbeTile() - 1u));
        if (any(greaterThanEqual(pixel, giFrame.size.xy))) continue;
        float depth;
        uint surface;
        giReadInput(pixel, depth, surface);
        if (giIsSky(depth)) continue;
        vec3 n = giSurfaceNormal(surface);
        vec3 p = giWorldPosition(giPixelUv(pixel), depth, giCamera.inverseViewProjection);
        if (dot(n, giFrame.camera.xyz - p) < 0.0) n = -n;  // the side the camera sees
        info = uvec4(pixel.x | (pixel.y << 16), floatBitsToUint(depth), packSnorm2x16(giOctEncode(n)), GI_PROBE_VALID);
        break;
    }
    probeInfo[tile.y * giFrame.tiles.x + tile.x] = info;
}
