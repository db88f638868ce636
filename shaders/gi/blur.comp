#version 450
#extension GL_GOOGLE_include_directive : require
#include "bricklight/bindings.glsl"
#include "gi_common.glsl"
// Pass 15: bilateral blur of diffuse and specular GI, separable (x, then y) but in one pass: a group
// loads its 16×16 pixels and a 4-pixel apron (24×24) into shared memory, blurs the apron's rows in x, and
// then the 16×16 in y over those results. The math is that of an x pass followed by a y pass; as two
// passes it was two levels of the frame (and a full-size intermediate written and read back).
// The radius follows the diffuse sample count: 4 pixels for fresh history, 1 when converged. Taps count
// by a Gaussian, by closeness to the pixel's plane and by normal similarity; specular taps also by
// similar roughness, and their radius shrinks with roughness (sharp reflections stay sharp). The output
// keeps the input's alpha (the sample count).
layout(local_size_x = 16, local_size_y = 16) in;
BL_TEXTURE(0) uniform sampler2D diffuseIn;
BL_TEXTURE(1) uniform sampler2D specularIn;
BL_TEXTURE(2) uniform sampler2D depthNow;
BL_TEXTURE(3) uniform usampler2D surfaceNow;
BL_IMAGE(0, rgba16f) uniform writeonly image2D diffuseOut;
BL_IMAGE(1, rgba16f) uniform writeonly image2D specularOut;

#define GI_BLUR_TAPS 4  // the widest radius
const int kTile = 16;
const int kApron = kTile + 2 * GI_BLUR_TAPS;  // 24

// The apron's pixels: position (w: 1 on a surface, 0 on sky or outside the image), the internal surface
// word (normal and roughness, decoded per tap) and the two inputs as half floats; then the x-blurred rows
// of the apron over the tile's 16 columns. 26.6 KiB in all (core/gi/gi_constants.h: kBlurSharedBytes;
// GL 4.5 and desktop Vulkan devices give at least 32 KiB).
shared vec4 tilePosition[kApron * kApron];
shared uint tileSurface[kApron * kApron];
shared uvec4 tileValues[kApron * kApron];  // xy diffuse, zw specular (packHalf2x16)
shared uvec4 rowBlurred[kApron * kTile];

vec4 unpackHalf4(uvec2 v) { return vec4(unpackHalf2x16(v.x), unpackHalf2x16(v.y)); }
uvec2 packHalf4(vec4 v) { return uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw)); }

// One output of a 1D blur: the centre `c` and its taps `tap(i)` (i in -taps..taps) in the apron; the tap
// values come from `values` (the inputs for x, the x-blurred rows for y).
struct BlurCentre {
    vec3 p, n;
    float roughness, distance, radius, specularRadius;
    int taps;
};

BlurCentre blurCentre(int c, float diffuseCount) {
    BlurCentre b;
    b.p = tilePosition[c].xyz;
    b.n = giSurfaceNormal(tileSurface[c]);
    b.roughness = giSurfaceRoughness(tileSurface[c]);
    b.distance = length(b.p - giFrame.camera.xyz);
    b.radius = mix(4.0, 1.0, clamp(diffuseCount / 16.0, 0.0, 1.0));
    b.taps = int(ceil(b.radius));
    b.specularRadius = b.radius * clamp(b.roughness * 2.0, 0.0, 1.0);
    return b;
}

// Adds tap i (apron index q, values v) to the sums.
void blurTap(BlurCentre b, int i, int q, vec4 dv, vec4 sv, inout vec4 dsum, inout vec4 ssum) {
    if (tilePosition[q].w == 0.0) return;  // sky or outside the image
    float plane = abs(dot(tilePosition[q].xyz - b.p, b.n)) / (0.005 * b.distance + 1e-6);
    uint surface = tileSurface[q];
    float geometry = exp(-plane * plane) * pow(max(dot(b.n, giSurfaceNormal(surface)), 0.0), 16.0);
    float x = float(i) / b.radius;
    float w = exp(-2.0 * x * x) * geometry;
    if (dv.a > 0.0 || i == 0) dsum += vec4(dv.rgb * w, w);
    float xs = b.specularRadius > 0.0 ? float(i) / b.specularRadius : (i == 0 ? 0.0 : 1e3);
    float ws = exp(-2.0 * xs * xs) * geometry * exp(-abs(giSurfaceRoughness(surface) - b.roughness) * 10.0);
    if (sv.a > 0.0 || i == 0) ssum += vec4(sv.rgb * ws, ws);
}

void main() {
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * kTile - GI_BLUR_TAPS;
    uint t = gl_LocalInvocationIndex;
    for (uint k = t; k < uint(kApron * kApron); k += uint(kTile * kTile)) {
        ivec2 q = origin + ivec2(int(k) % kApron, int(k) / kApron);
        vec4 position = vec4(0.0), d = vec4(0.0), s = vec4(0.0);
        uint surface = 0u;
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(uvec2(q), giFrame.size.xy))) {
            d = texelFetch(diffuseIn, q, 0);
            s = texelFetch(specularIn, q, 0);
            float depth = texelFetch(depthNow, q, 0).r;
            surface = texelFetch(surfaceNow, q, 0).r;
            if (!giIsSky(depth)) position = vec4(giWorldPosition(giPixelUv(uvec2(q)), depth, giCamera.inverseViewProjection), 1.0);
        }
        tilePosition[k] = position;
        tileSurface[k] = surface;
        tileValues[k] = uvec4(packHalf4(d), packHalf4(s));
    }
    barrier();
    // x: every apron row, the tile's columns.
    for (uint k = t; k < uint(kApron * kTile); k += uint(kTile * kTile)) {
        int row = int(k) / kTile, column = int(k) % kTile + GI_BLUR_TAPS;
        int c = row * kApron + column;
        vec4 d0 = unpackHalf4(tileValues[c].xy), s0 = unpackHalf4(tileValues[c].zw);
        vec4 d = d0, s = s0;
        if (tilePosition[c].w != 0.0) {
            BlurCentre b = blurCentre(c, d0.a);
            vec4 dsum = vec4(0.0), ssum = vec4(0.0);
            for (int i = -b.taps; i <= b.taps; ++i) {
                int q = c + i;
                blurTap(b, i, q, unpackHalf4(tileValues[q].xy), unpackHalf4(tileValues[q].zw), dsum, ssum);
            }
            d = vec4(dsum.w > 0.0 ? dsum.rgb / dsum.w : d0.rgb, d0.a);
            s = vec4(ssum.w > 0.0 ? ssum.rgb / ssum.w : s0.rgb, s0.a);
        }
        rowBlurred[k] = uvec4(packHalf4(d), packHalf4(s));
    }
    barrier();
    // y: the tile, over the x-blurred rows.
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), giFrame.size.xy))) return;
    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    int c = (local.y + GI_BLUR_TAPS) * kApron + local.x + GI_BLUR_TAPS;
    int r = (local.y + GI_BLUR_TAPS) * kTile + local.x;
    vec4 d0 = unpackHalf4(rowBlurred[r].xy), s0 = unpackHalf4(rowBlurred[r].zw);
    vec4 d = d0, s = s0;
    if (tilePosition[c].w != 0.0) {
        BlurCentre b = blurCentre(c, d0.a);
        vec4 dsum = vec4(0.0), ssum = vec4(0.0);
        for (int i = -b.taps; i <= b.taps; ++i) {
            int q = c + i * kApron, rq = r + i * kTile;
            blurTap(b, i, q, unpackHalf4(rowBlurred[rq].xy), unpackHalf4(rowBlurred[rq].zw), dsum, ssum);
        }
        d = vec4(dsum.w > 0.0 ? dsum.rgb / dsum.w : d0.rgb, d0.a);
        s = vec4(ssum.w > 0.0 ? ssum.rgb / ssum.w : s0.rgb, s0.a);
    }
    imageStore(diffuseOut, pixel, d);
    imageStore(specularOut, pixel, s);
}
