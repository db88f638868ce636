// What the cone-tracing passes (trace_diffuse, resolve_diffuse, trace_specular) share: their parameters (a read
// buffer written by vct::ConeTracer each frame, so that no branch depends on constants alone — see
// docs/notes/soak.md), the G-buffer, the guide (world position and normal per pixel), the cones of a pixel.
#include "bricklight/bindings.glsl"
#include "bricklight/cone_trace.glsl"

BL_READ_BUFFER(6) TraceParams {
    mat4 inverseViewProjection;
    mat4 previousViewProjection;
    vec4 eye;                 // xyz camera position
    uvec4 size;               // xy display size, z sparsity (pixels per block side), w frame
    uvec4 lowSize;            // xy sparse grid, z diffuse cones, w flags (1: reset history, 2: motion vectors given)
    vec4 normalUnpackScale;   // xyz; w: roughness channel
    vec4 normalUnpackOffset;  // xyz; w: the largest roughness a specular cone takes
    vec4 cone;                // x diffuse cone factor, y diffuse tracing step, z opacity correction, w initial offset (voxels)
    vec4 limits;              // x max distance (world), y ambient range (world), z temporal weight, w light-leak lag
    uvec4 sparseOffset;       // xy: the pixel of each block traced this frame; z: the specular tracing step (float bits);
                              // w: this frame's turn of the diffuse cones (float bits, radians)
} trace;

BL_TEXTURE(0) uniform sampler2D gDepth;
BL_TEXTURE(1) uniform sampler2D gNormals;
BL_TEXTURE(2) uniform sampler2D gRoughness;
BL_TEXTURE(3) uniform sampler2D gMotion;

const uint FLAG_RESET = 1u, FLAG_MOTION = 2u;

bool isSky(float depth) { return !(depth < 1.0); }

vec3 worldPosition(ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(trace.size.xy) * 2.0 - 1.0;
    vec4 p = trace.inverseViewProjection * vec4(ndc, depth, 1.0);
    return p.xyz / p.w;
}

vec3 surfaceNormal(ivec2 pixel) {
    vec3 n = texelFetch(gNormals, pixel, 0).xyz * trace.normalUnpackScale.xyz + trace.normalUnpackOffset.xyz;
    return dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
}

// The guide: the surface a pixel (or a block's traced pixel) saw, bit-exact in an RGBA32_UINT texel.
uvec4 packGuide(vec3 position, vec3 normal) {
    vec2 o = normal.xy / (abs(normal.x) + abs(normal.y) + abs(normal.z));  // octahedral
    o = normal.z >= 0.0 ? o : (1.0 - abs(o.yx)) * vec2(o.x >= 0.0 ? 1.0 : -1.0, o.y >= 0.0 ? 1.0 : -1.0);
    return uvec4(floatBitsToUint(position), packSnorm2x16(o));
}
const uvec4 NO_GUIDE = uvec4(0x7FC00000u, 0u, 0u, 0u);  // a NaN position: nothing there
bool unpackGuide(uvec4 g, out vec3 position, out vec3 normal) {
    position = uintBitsToFloat(g.xyz);
    vec2 o = unpackSnorm2x16(g.w);
    normal = vec3(o, 1.0 - abs(o.x) - abs(o.y));
    if (normal.z < 0.0) normal.xy = (1.0 - abs(normal.yx)) * vec2(normal.x >= 0.0 ? 1.0 : -1.0, normal.y >= 0.0 ? 1.0 : -1.0);
    normal = normalize(normal);
    return g.x != NO_GUIDE.x;
}

// The finest voxel size of the level that holds a world point (cones start that many voxels off the surface).
float voxelSizeAt(vec3 position) {
    uint level = blVctHoldingLevel(0u, position / blVctFrame.scales.x, 1.0, blVctFrame.params.y, float(blVctFrame.params.x));
    return blVctFrame.scales.x * float(1u << min(level, blVctFrame.params.y - 1u));
}

BlCone coneAt(vec3 position, vec3 normal, vec3 direction, float coneFactor) {
    float voxel = voxelSizeAt(position);
    BlCone c = blDefaultCone(position + normal * (trace.cone.w * voxel), direction, coneFactor);
    c.firstSampleT = 0.0;
    c.tracingStep = trace.cone.y;
    c.opacityCorrection = trace.cone.z;
    // Without emittance (voxel AO) nothing beyond the ambient range matters: the cone stops there.
    bool occlusionOnly = blVctFrame.params.z == 0u;
    c.maxDistance = occlusionOnly ? (trace.limits.x > 0.0 ? min(trace.limits.x, trace.limits.y) : trace.limits.y) : trace.limits.x;
    c.ambientRange = trace.limits.y;
    c.lightLeakLag = uint(trace.limits.w);
    return c;
}

// Diffuse light at a surface: `cones` cones spread cosine-weighted over the hemisphere (a Fibonacci spiral,
// turned by `rotation` radians: the same for every pixel of a frame, so that neighbouring pixels' cones take the
// same faces and branches; another each frame for the temporal blend), so the mean of their radiance is
// irradiance / π. w: the mean transmittance
// at the ambient range (ambient occlusion).
vec4 diffuseAt(vec3 position, vec3 normal, float rotation) {
    vec3 helper = abs(normal.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangent = normalize(cross(helper, normal));
    vec3 bitangent = cross(normal, tangent);
    uint cones = clamp(trace.lowSize.z, 1u, 32u);
    vec4 sum = vec4(0.0);
    for (uint k = 0u; k < cones; ++k) {
        float u = (float(k) + 0.5) / float(cones);
        float radius = sqrt(u);
        float phi = float(k) * 2.39996323 + rotation;
        vec3 d = normalize(radius * cos(phi) * tangent + radius * sin(phi) * bitangent + sqrt(max(1.0 - u, 0.0)) * normal);
        BlConeResult r = blTraceCone(coneAt(position, normal, d, trace.cone.x));
        sum += vec4(r.radiance, r.ambient);
    }
    return sum / float(cones);
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
