// Shared by the GI passes: the frame constants, the internal G-buffer encoding, position reconstruction,
// the probe direction mapping, random numbers and the environment. Mirrors core/gi/gi_constants.h.
#ifndef BRICKLIGHT_GI_COMMON_GLSL
#define BRICKLIGHT_GI_COMMON_GLSL

#include "bricklight/rgb9e5.glsl"

#define GI_PI 3.14159265358979

BL_CONSTANTS(0) uniform GiCamera {
    mat4 viewProjection;
    mat4 inverseViewProjection;
    mat4 previousViewProjection;
    mat4 previousInverseViewProjection;
} giCamera;

BL_CONSTANTS(1) uniform GiFrame {
    uvec4 size;          // xy internal size, zw display size
    uvec4 tiles;         // xy probe tiles (giProbeTile()² internal pixels each), z frame index, w flags (GI_FLAG_*)
    vec4 camera;         // xyz camera position, w finest traced voxel size
    vec4 normalScale;    // xyz normal unpack scale, w roughness threshold (perceptual)
    vec4 normalOffset;   // xyz normal unpack offset, w environment intensity
    uvec4 inputs;        // x roughness channel, y roughness is perceptual, z environment kind, w max history
    vec4 motion;         // xy motion vector scale
    vec4 trace;          // x diffuse push-off, y specular push-off, z tMin, w tMax
    uvec4 cascades;      // x start, y end (clamped), z atlas bricks per axis, w brick capacity
    vec4 epsilon;        // x diffuse epsilon scale, y specular epsilon scale
    uvec4 relight;       // x light count, y relight flags (GI_RELIGHT_*)
    vec4 traceLimits;    // x iterations per cascade of every GI ray, y diffuse rays' coarsen-after voxels
    uvec4 probes;        // x probe tile side in internal pixels (8 or 16; ContextDesc::probeTile)
    uvec4 cache;         // x radiance cache slots kept for injections that carry light (inject_radiance.comp),
                         // y changed regions (GiChangedRegions)
} giFrame;

#define GI_CHANGE_HISTORY 2.0       // core/gi/gi_constants.h: kChangeHistory
#define GI_CHANGE_FEEDBACK_FRAMES 2.0  // ... kChangeFeedbackFrames

#ifdef GI_USES_CHANGED_REGIONS
// World boxes (min, max) where the field's geometry just changed (a mover's old and new place), grown by their
// reach (core/gi/gi_constants.h: kMaxChangedRegions, kChangeReachVoxels); giFrame.cache.y of them.
BL_CONSTANTS(3) uniform GiChangedRegions { vec4 boxes[16]; } giChanged;

// Whether the box [lo, hi] touches one of them that changed less than `frames` frames ago (boxes[2i].w: its age).
bool giInChangedRegion(vec3 lo, vec3 hi, float frames) {
    for (uint i = 0u; i < giFrame.cache.y; ++i)
        if (giChanged.boxes[2u * i].w < frames && all(lessThanEqual(giChanged.boxes[2u * i].xyz, hi)) &&
            all(lessThanEqual(lo, giChanged.boxes[2u * i + 1u].xyz)))
            return true;
    return false;
}
#endif

#define GI_RELIGHT_ALBEDO 1u    // bricks learn their albedo; unseen texels are re-lit (relight_cache.comp)
#define GI_RELIGHT_EMISSION 2u  // ...and their emission
#define GI_RELIGHT_EMISSION_IN_RAYS 4u  // the lit image leaves emission out: relight rays add it at their hits
#define GI_RELIGHT_EMITTERS_IN_LIGHTS 8u  // the lights hold every emitter: relight rays take no emission at their hits
#define GI_RELIGHT_LIT_HOLDS_EMISSION 16u  // the lit image (so the cache) holds the emission: unseen hits add the field's
#define GI_RELIGHT_DIRECT_ONLY 32u  // re-lit texels and unseen hits take the lights and emission only (one bounce)
#define GI_RELIGHT_UNSEEN_HITS 64u  // the lights hold all direct light: probe rays light the surfaces no view has lit
#define GI_RELIGHT_ENVIRONMENT_IN_DIRECT 128u  // the direct lighting holds the environment: pixels' rays take none of it
// Per-brick material (GI_MATERIAL_WORDS uints per brick): albedo RGBA8 (a = 1 once learnt), emission
// RGB9E5 (0: none), the frame index + 1 at which the camera last saw the brick (0: never).
#define GI_MATERIAL_WORDS 3u
// Relighting (relight_cache.comp): a brick out of view that the camera has not seen for GI_RELIGHT_AFTER
// frames (twice the injection's rotation through its 2×2 tiles; × 2^k in the k-th cascade above the
// start) — or any brick not seen for GI_RELIGHT_STALE (× 2^k) frames — is re-lit every
// GI_RELIGHT_PERIOD-th frame; at most GI_RELIGHT_BUDGET bricks per frame (core/gi/gi_constants.h:
// kRelightBudget).
#define GI_RELIGHT_AFTER 4u
#define GI_RELIGHT_STALE 8u
#define GI_RELIGHT_PERIOD 2u
#define GI_RELIGHT_BUDGET 2048u
// A relight list entry's flag: a brick holding cards (alpha-tested surfaces) listed while in view, for its cards'
// sides the camera does not see (relight_cache.comp); whole bricks are listed without it.
#define GI_RELIGHT_CARD_SIDES 0x80000000u
// How often such a brick is listed: every 2nd frame made the relight pass of the foliage scene about ten times
// slower.
#define GI_RELIGHT_CARD_PERIOD 8u

// Cache slots (core/gi/gi_constants.h): per brick, the slot of the radiance cache that holds its 4³
// texels, or GI_SLOT_NONE; GI_SLOT_PENDING while inject_radiance.comp allocates one. The slots are laid out
// 64 × 64 × n in the cache image, 4³ texels each.
#define GI_SLOT_NONE 0xFFFFFFFFu
#define GI_SLOT_PENDING 0xFFFFFFFEu
ivec3 giCacheSlotBase(uint slot) { return ivec3(slot % 64u, (slot / 64u) % 64u, slot / 4096u) * 4; }

// The world cache's share of the irradiance where screen probes exist (the rest is the probes'; blended
// per probe in project_probes.comp). The screen probes see this view's detail; the world cache is stable,
// and the fallback where probes are missing.
#define GI_WORLD_SHARE 0.3

#define GI_FLAG_REVERSED_DEPTH 1u
#define GI_FLAG_RESET_HISTORY 2u
#define GI_FLAG_HISTORY_VALID 8u   // a previous frame exists (not the first dispatch)
#define GI_FLAG_CAMERA_MOTION 16u  // no motion vectors given: the motion of a still world under the camera
#define GI_FLAG_PROBE_PARALLAX 32u  // the probes' reprojection tests parallax (ContextFlags::NoProbeParallax off)

#define GI_ENV_NONE 0u
#define GI_ENV_CUBE 1u
#define GI_ENV_EQUIRECT 2u

bool giHasFlag(uint flag) { return (giFrame.tiles.w & flag) != 0u; }
uint giFrameIndex() { return giFrame.tiles.z; }
uint giProbeTile() { return giFrame.probes.x; }

// Depth: the application's convention (1 = far, or 0 with reversed depth); sky where nothing was drawn.
float giSkyDepth() { return giHasFlag(GI_FLAG_REVERSED_DEPTH) ? 0.0 : 1.0; }
bool giIsSky(float depth) {
    return giHasFlag(GI_FLAG_REVERSED_DEPTH) ? !(depth > 0.0) : !(depth < 1.0);
}

bool giFinite(float x) { return !isnan(x) && !isinf(x); }
bool giFinite(vec3 v) { return giFinite(v.x) && giFinite(v.y) && giFinite(v.z); }

// World position of an internal pixel (uv in [0,1], origin top-left) at device depth d.
vec3 giWorldPosition(vec2 uv, float depth, mat4 inverseViewProjection) {
    vec4 p = inverseViewProjection * vec4(uv * 2.0 - 1.0, depth, 1.0);
    return p.xyz / p.w;
}
vec2 giPixelUv(uvec2 pixel) { return (vec2(pixel) + 0.5) / vec2(giFrame.size.xy); }

// Octahedral unit-vector encoding.
vec2 giOctEncode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return e;
}
vec3 giOctDecode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    float t = max(-n.z, 0.0);
    n.xy += vec2(n.x >= 0.0 ? -t : t, n.y >= 0.0 ? -t : t);
    return normalize(n);
}

// Internal G-buffer texel (R32_UINT): normal as 2×12-bit octahedral, perceptual roughness in 8 bits.
uint giPackSurface(vec3 n, float roughness) {
    uvec2 e = uvec2(clamp(giOctEncode(n) * 0.5 + 0.5, 0.0, 1.0) * 4095.0 + 0.5);
    return e.x | (e.y << 12) | (uint(clamp(roughness, 0.0, 1.0) * 255.0 + 0.5) << 24);
}
vec3 giSurfaceNormal(uint s) { return giOctDecode(vec2(uvec2(s, s >> 12) & 4095u) / 4095.0 * 2.0 - 1.0); }
float giSurfaceRoughness(uint s) { return float(s >> 24) / 255.0; }

// Basis around a unit normal (Duff et al. 2017).
void giBasis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Probe texels: the 8×8 square maps to the hemisphere around the probe normal by the equal-area
// concentric mapping (Shirley-Chiu disk, z = 1 - r²): every texel covers the same solid angle 2π/64.
vec3 giSquareToHemisphere(vec2 u) {
    vec2 a = u * 2.0 - 1.0;
    float r, phi;
    if (a.x == 0.0 && a.y == 0.0) return vec3(0.0, 0.0, 1.0);
    if (abs(a.x) > abs(a.y)) {
        r = a.x;
        phi = (GI_PI / 4.0) * (a.y / a.x);
    } else {
        r = a.y;
        phi = GI_PI / 2.0 - (GI_PI / 4.0) * (a.x / a.y);
    }
    float s = r * sqrt(max(2.0 - r * r, 0.0));
    return vec3(s * cos(phi), s * sin(phi), 1.0 - r * r);
}
vec2 giHemisphereToSquare(vec3 d) {
    float r = sqrt(max(1.0 - d.z, 0.0));
    float phi = atan(d.y, d.x);
    if (phi < -GI_PI / 4.0) phi += 2.0 * GI_PI;
    vec2 a;
    if (phi < GI_PI / 4.0) {
        a.x = r;
        a.y = phi * r / (GI_PI / 4.0);
    } else if (phi < 3.0 * GI_PI / 4.0) {
        a.y = r;
        a.x = -(phi - GI_PI / 2.0) * r / (GI_PI / 4.0);
    } else if (phi < 5.0 * GI_PI / 4.0) {
        a.x = -r;
        a.y = (phi - GI_PI) * a.x / (GI_PI / 4.0);
    } else {
        a.y = -r;
        a.x = -(phi - 3.0 * GI_PI / 2.0) * a.y / (GI_PI / 4.0);
    }
    return clamp(a * 0.5 + 0.5, 0.0, 1.0);
}
vec3 giProbeLocalToWorld(vec3 l, vec3 n, vec3 t, vec3 b) { return normalize(t * l.x + b * l.y + n * l.z); }
vec3 giProbeDirection(vec3 n, vec2 u) {
    vec3 t, b;
    giBasis(n, t, b);
    return giProbeLocalToWorld(giSquareToHemisphere(u), n, t, b);
}

// Random numbers: PCG hash.
uint giPcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
float giRandom(inout uint state) {
    state = giPcg(state);
    return float(state >> 8) / 16777216.0;
}
vec2 giHammersley(uint i, uint n) {
    uint b = bitfieldReverse(i);
    return vec2(float(i) / float(n), float(b) * 2.3283064365386963e-10);
}

// Probe tile info (uvec4): x = pixel x | pixel y << 16, y = device depth bits, z = normal (snorm oct),
// w = flags: bit 0 valid, bit 1 reprojected from the previous frame.
#define GI_PROBE_VALID 1u
#define GI_PROBE_REPROJECTED 2u
// Probe texel alpha: what the texel's value is.
#define GI_TEXEL_EMPTY 0.0        // nothing (not traced, or not carried over by reprojection)
#define GI_TEXEL_UNKNOWN_HIT 0.5  // the ray hit a surface whose radiance no cache holds yet
#define GI_TEXEL_MISS 0.75        // the environment
#define GI_TEXEL_HIT 1.0          // the radiance cache at the hit
// A hit's texel holds GI_TEXEL_HIT + the hit's distance (world units) in its alpha, for the reprojection's parallax
// test (reproject_probes.comp). A negative alpha marks a texel the reprojection carried over whose hit may lie in
// another direction from the new probe: fill_probes traces it that frame or empties it.
uvec2 giProbePixel(uvec4 info) { return uvec2(info.x & 0xFFFFu, info.x >> 16); }
vec3 giProbeNormal(uvec4 info) { return giOctDecode(unpackSnorm2x16(info.z)); }

#ifdef BRICKLIGHT_TRACE_GLSL
// A GI ray through the frame's cascades, with its tMin and iteration budget. Diffuse rays (a cone each)
// coarsen with distance and use the diffuse epsilon; specular rays coarsen by their lobe
// (giMakeSpecularRay), shadow rays not at all.
#define GI_RAY_DIFFUSE 0u
#define GI_RAY_SPECULAR 1u
#define GI_RAY_SHADOW 2u
BlSdfRay giMakeRay(vec3 origin, vec3 direction, float tMax, uint kind) {
    BlSdfRay ray = blSdfMakeRay(origin, direction, giFrame.trace.z, tMax);
    ray.startCascade = giFrame.cascades.x;
    ray.endCascade = giFrame.cascades.y;
    ray.epsilonScale = kind == GI_RAY_SPECULAR ? giFrame.epsilon.y : giFrame.epsilon.x;
    ray.maxIterations = uint(giFrame.traceLimits.x);
    if (kind == GI_RAY_DIFFUSE) ray.coarsenAfterVoxels = giFrame.traceLimits.y;
    return ray;
}
// A specular ray of GGX roughness α: its lobe is a cone too. The half-vectors spread about 1.3α across at half maximum
// and reflection doubles that, so the lobe is about 2.6α·t wide at distance t. It coarsens once that footprint reaches
// the one at which a diffuse ray (a probe texel, about 0.35 rad across) does, and never sooner than a diffuse ray:
// after max(1, 0.35 / 2.6α) times the diffuse rays' voxels. Near-mirrors (small α) hardly coarsen.
BlSdfRay giMakeSpecularRay(vec3 origin, vec3 direction, float tMax, float alpha) {
    BlSdfRay ray = giMakeRay(origin, direction, tMax, GI_RAY_SPECULAR);
    if (giFrame.traceLimits.y > 0.0 && alpha > 1e-3) ray.coarsenAfterVoxels = giFrame.traceLimits.y * max(1.0, 0.35 / (2.6 * alpha));
    return ray;
}
#endif

#endif
