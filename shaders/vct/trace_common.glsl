// What the cone-tracing passes (trace_diffuse, resolve_diffuse, trace_specular) share: their parameters (a read
// buffer written by vct::ConeTracer each frame, so that no branch depends on constants alone — see
// docs/notes/soak.md), the G-buffer, the guide (world position and normal per pixel), the cones of a pixel.
#include "bricklight/bindings.glsl"
#include "bricklight/cone_trace.glsl"
#ifdef VCT_SDF_OCCLUSION  // the *_sdf.comp variants: cones stop where a ray through the distance field meets a surface
#define BL_SDF_READ_BUFFER_BASE 0  // 0..3 (6 and 7 are the parameters and the clip-map's frame); atlas at 15
#include "bricklight/trace.glsl"
#endif

BL_READ_BUFFER(6) TraceParams {
    mat4 inverseViewProjection;
    mat4 previousViewProjection;
    mat4 previousInverseViewProjection;
    vec4 eye;                 // xyz camera position
    uvec4 size;               // xy display size, z sparsity (pixels per block side), w frame
    uvec4 lowSize;            // xy sparse grid, z diffuse cones, w flags (1: reset history, 2: motion vectors given)
    vec4 normalUnpackScale;   // xyz; w: roughness channel
    vec4 normalUnpackOffset;  // xyz; w: the largest roughness a specular cone takes
    vec4 cone;                // x diffuse cone factor, y diffuse tracing step, z opacity correction, w initial offset (voxels)
    vec4 limits;              // x max distance (world), y ambient range (world), z temporal weight, w light-leak lag
    uvec4 sparseOffset;       // xy: the pixel of each block traced this frame; z: the specular tracing step (float bits);
                              // w: this frame's turn of the diffuse cones (float bits, radians)
    vec4 specular;            // x: tangent jitter (0..1 of the cone's half width), y: the frame (float), z: the refinement's
                              // cone results (float; refine_list.glsl)
} trace;

BL_TEXTURE(0) uniform sampler2D gDepth;
BL_TEXTURE(1) uniform sampler2D gNormals;
BL_TEXTURE(2) uniform sampler2D gRoughness;
BL_TEXTURE(3) uniform sampler2D gMotion;

const uint FLAG_RESET = 1u, FLAG_MOTION = 2u;

bool isSky(float depth) { return !(depth < 1.0); }

// The world point at a pixel's centre and device depth, through a frame's inverse view-projection.
vec3 unprojectPixel(mat4 inverseViewProjection, ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(trace.size.xy) * 2.0 - 1.0;
    vec4 p = inverseViewProjection * vec4(ndc, depth, 1.0);
    return p.xyz / p.w;
}
vec3 worldPosition(ivec2 pixel, float depth) { return unprojectPixel(trace.inverseViewProjection, pixel, depth); }

vec3 surfaceNormal(ivec2 pixel) {
    vec3 n = texelFetch(gNormals, pixel, 0).xyz * trace.normalUnpackScale.xyz + trace.normalUnpackOffset.xyz;
    return dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
}

uint packOctahedral(vec3 normal) {
    vec2 o = normal.xy / (abs(normal.x) + abs(normal.y) + abs(normal.z));
    o = normal.z >= 0.0 ? o : (1.0 - abs(o.yx)) * vec2(o.x >= 0.0 ? 1.0 : -1.0, o.y >= 0.0 ? 1.0 : -1.0);
    return packSnorm2x16(o);
}
vec3 unpackOctahedral(uint word) {
    vec2 o = unpackSnorm2x16(word);
    vec3 normal = vec3(o, 1.0 - abs(o.x) - abs(o.y));
    if (normal.z < 0.0) normal.xy = (1.0 - abs(normal.yx)) * vec2(normal.x >= 0.0 ? 1.0 : -1.0, normal.y >= 0.0 ? 1.0 : -1.0);
    return normalize(normal);
}

// The guide of a block's traced pixel: the surface it saw, bit-exact in an RGBA32_UINT texel (the upsample weighs
// each pixel by its distance from that surface's plane).
uvec4 packGuide(vec3 position, vec3 normal) { return uvec4(floatBitsToUint(position), packOctahedral(normal)); }
const uvec4 NO_GUIDE = uvec4(0x7FC00000u, 0u, 0u, 0u);  // a NaN position: nothing there
bool unpackGuide(uvec4 g, out vec3 position, out vec3 normal) {
    position = uintBitsToFloat(g.xyz);
    normal = unpackOctahedral(g.w);
    return g.x != NO_GUIDE.x;
}

// The guide of a full-resolution pixel, for the next frame's temporal test: its device depth and normal in an
// RG32_UINT texel — half the bytes of a position's; the next frame rebuilds the position through this frame's
// inverse view-projection (trace.previousInverseViewProjection), to float precision, far inside the test's half voxel.
uvec2 packPixelGuide(float depth, vec3 normal) { return uvec2(floatBitsToUint(depth), packOctahedral(normal)); }
const uvec2 NO_PIXEL_GUIDE = uvec2(0x7FC00000u, 0u);  // a NaN depth: nothing there
bool unpackPreviousPixelGuide(uvec2 g, ivec2 previous, out vec3 position, out vec3 normal) {
    position = unprojectPixel(trace.previousInverseViewProjection, previous, uintBitsToFloat(g.x));
    normal = unpackOctahedral(g.y);
    return g.x != NO_PIXEL_GUIDE.x;
}

// The surface a pixel's reprojected history saw last frame (`guide`, last frame's pixel guide at `previous`) is this
// one: within half a voxel (`voxel` world units, the level's at the surface) and facing the same way.
bool sameSurfaceLastFrame(uvec2 guide, ivec2 previous, vec3 position, vec3 normal, float voxel) {
    vec3 p, n;
    return unpackPreviousPixelGuide(guide, previous, p, n) && distance(p, position) < 0.5 * voxel && dot(n, normal) > 0.9;
}

// The finest voxel size of the level that holds a world point (cones start that many voxels off the surface).
float voxelSizeAt(vec3 position) {
    uint level = blVctHoldingLevel(0u, position / blVctFrame.scales.x, 1.0, blVctFrame.params.y, float(blVctFrame.params.x));
    return blVctFrame.scales.x * float(1u << min(level, blVctFrame.params.y - 1u));
}

// A cone from a surface whose level's finest voxel is `voxel` (voxelSizeAt) world units wide.
BlCone coneAtVoxel(vec3 position, float voxel, vec3 normal, vec3 direction, float coneFactor) {
    BlCone c = blDefaultCone(position + normal * (trace.cone.w * voxel), direction, coneFactor);
    c.firstSampleT = 0.0;
    c.planeNormal = normal;
    c.planeDistance = trace.cone.w * voxel;
    c.tracingStep = trace.cone.y;
    c.opacityCorrection = trace.cone.z;
    // Without emittance (voxel AO) nothing beyond the ambient range matters: the cone stops there.
    bool occlusionOnly = blVctFrame.params.z == 0u;
    c.maxDistance = occlusionOnly ? (trace.limits.x > 0.0 ? min(trace.limits.x, trace.limits.y) : trace.limits.y) : trace.limits.x;
    c.ambientRange = trace.limits.y;
    c.lightLeakLag = uint(trace.limits.w);
#ifdef VCT_SDF_OCCLUSION
    // As far as the cone may go (the coarsest level's half width when unbounded).
    float reach = c.maxDistance > 0.0 ? c.maxDistance : 0.5 * blVctFrame.scales.x * float(blVctFrame.params.x << (blVctFrame.params.y - 1u));
    BlSdfRay ray = blSdfMakeRay(c.origin, direction, 0.0, reach);
    // Traced as a cone, as the SDF GI traces its probe rays: coarser cascades once the cone outgrows the voxel (never
    // sooner than 4 voxels), and a bounded budget per cascade (a ray that runs out goes on in the next; one that
    // runs out in the last gives no stop, and the voxels alone decide).
    ray.coarsenAfterVoxels = max(4.0, 1.0 / max(coneFactor, 1.0e-3));
    ray.maxIterations = 32u;
    BlSdfHit hit = blSdfTrace(ray);
    c.surfaceDistance = hit.hit ? max(hit.t, 1.0e-6) : 0.0;
#endif
    return c;
}

BlCone coneAt(vec3 position, vec3 normal, vec3 direction, float coneFactor) {
    return coneAtVoxel(position, voxelSizeAt(position), normal, direction, coneFactor);
}

// What a surface's diffuse cones share: its normal's tangent frame and the voxel size there, found once for all of
// them (a level search and two square roots a cone otherwise).
struct DiffuseFrame {
    vec3 tangent, bitangent;
    float voxel;
};
DiffuseFrame diffuseFrame(vec3 position, vec3 normal) {
    DiffuseFrame f;
    vec3 helper = abs(normal.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    f.tangent = normalize(cross(helper, normal));
    f.bitangent = cross(normal, f.tangent);
    f.voxel = voxelSizeAt(position);
    return f;
}

// Diffuse cone k of `cones` at a surface: spread cosine-weighted over the hemisphere (a Fibonacci spiral, turned by
// `rotation` radians: the same for every pixel of a frame, so that neighbouring pixels' cones take the same faces
// and branches; another each frame for the temporal blend), so that the mean of the cones' radiance is irradiance / π.
BlCone diffuseCone(uint k, uint cones, vec3 position, vec3 normal, float rotation, DiffuseFrame frame) {
    float u = (float(k) + 0.5) / float(cones);
    float radius = sqrt(u);
    float phi = float(k) * 2.39996323 + rotation;
    vec3 d = normalize(radius * cos(phi) * frame.tangent + radius * sin(phi) * frame.bitangent + sqrt(max(1.0 - u, 0.0)) * normal);
    return coneAtVoxel(position, frame.voxel, normal, d, trace.cone.x);
}

uint diffuseConeCount() { return clamp(trace.lowSize.z, 1u, 32u); }

// Diffuse light at a surface: rgb irradiance / π, w the mean transmittance at the ambient range (ambient occlusion).
vec4 diffuseAt(vec3 position, vec3 normal, float rotation) {
    uint cones = diffuseConeCount();
    DiffuseFrame frame = diffuseFrame(position, normal);
    vec4 sum = vec4(0.0);
    for (uint k = 0u; k < cones; ++k) {
        BlConeResult r = blTraceCone(diffuseCone(k, cones, position, normal, rotation, frame));
        sum += vec4(r.radiance, r.ambient);
    }
    return sum / float(cones);
}

// The specular cone of a pixel: along the mirror direction, as wide as the roughness says (VXGI 1.0: coneFactor =
// roughness² · √π, roughness clamped to the largest a cone takes).
BlCone specularCone(ivec2 pixel, vec3 position, vec3 normal) {
    vec4 r4 = texelFetch(gRoughness, pixel, 0);
    uint channel = uint(trace.normalUnpackScale.w);
    float roughness = clamp(channel == 0u ? r4.x : (channel == 1u ? r4.y : (channel == 2u ? r4.z : r4.w)), 0.0, trace.normalUnpackOffset.w);
    vec3 view = normalize(trace.eye.xyz - position);
    vec3 direction = reflect(-view, normal);
    float coneFactor = max(roughness * roughness * 1.7724539, 0.01);
    // Tangent jitter (VXGI's): a narrower cone whose axis wanders over the wide one's width, a new point per frame
    // and pixel; the temporal blend averages them into the wide cone's light with the narrow one's detail.
    float jitter = clamp(trace.specular.x, 0.0, 1.0);
    uint h = uint(pixel.x) * 73856093u ^ uint(pixel.y) * 19349663u;
    h = (h ^ (h >> 16)) * 0x45d9f3bu;
    float u1 = fract(float(h & 0xFFFFu) / 65536.0 + trace.specular.y * 0.61803399);
    float u2 = fract(float(h >> 16) / 65536.0 + trace.specular.y * 0.75487767);
    vec3 helper = abs(direction.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangent = normalize(cross(helper, direction));
    vec3 bitangent = cross(direction, tangent);
    float offset = 0.5 * coneFactor * jitter * sqrt(u1);
    vec3 jittered = normalize(direction + offset * (cos(6.2831853 * u2) * tangent + sin(6.2831853 * u2) * bitangent));
    // Never below the surface.
    direction = dot(jittered, normal) > 0.02 ? jittered : direction;
    coneFactor = max(coneFactor * (1.0 - 0.5 * jitter), 0.01);
    BlCone cone = coneAt(position, normal, direction, coneFactor);
    cone.tracingStep = uintBitsToFloat(trace.sparseOffset.z);
    return cone;
}

// Where a pixel's surface was last frame, in pixels; false when off screen.
bool previousPixel(ivec2 pixel, vec3 position, out ivec2 previous) {
    vec2 uv;
    if ((trace.lowSize.w & FLAG_MOTION) != 0u) {
        uv = (vec2(pixel) + 0.5) / vec2(trace.size.xy) - texelFetch(gMotion, pixel, 0).xy;
    } else {
        vec4 clip = trace.previousViewProjection * vec4(position, 1.0);
        uv = clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : vec2(-1.0);
    }
    previous = ivec2(floor(uv * vec2(trace.size.xy)));
    return all(greaterThanEqual(previous, ivec2(0))) && all(lessThan(previous, ivec2(trace.size.xy)));
}
