// The renderer's emittance for voxel cone tracing (blVoxelEmittance, bricklight/voxelize.glsl), included by
// voxel_emittance.frag and voxel_emittance_solid.frag: the light a surface sends, as the renderer's direct
// lighting computes it — the emitters (next-event estimation), point and spot lights, the sun and the sky,
// shadowed by rays through the scene's BVH — times the diffuse albedo.
// Like the lit image GI feeds on, it leaves the emitters' own emission out (direct lighting samples them; cone
// tracing is the indirect light). Deterministic per point, so voxels do not flicker from frame to frame. With
// bounces on, the light the voxels gathered last frame (blVoxelIndirect) is reflected too, one bounce more each
// frame.
#define BL_VOXEL_MULTI_BOUNCE
// With --vct-occlusion sdf the bounce cones stop at the first surface the scene's BVH meets along their axis (the
// exact distance the cone tracer takes from the distance field).
float bounceConeSurface(vec3 origin, vec3 direction);
#define BL_VOXEL_CONE_SURFACE bounceConeSurface
// Alpha-tested materials block and send light by their coverage (voxel_alpha.glsl) where the including shader
// defines BL_VOXEL_COVERAGE (voxel_emittance.frag); opaque ones return 1 at once and write the same words as
// without the hook. Without the define (voxel_emittance_solid.frag) every surface is solid.
#include "bricklight/voxelize.glsl"
BL_CONSTANTS(0) uniform VoxelLighting {
    uvec4 params;  // x light samples per fragment, y 1: add last frame's indirect light, z 1: cones stop at surfaces
} voxelLighting;
#define BL_SCENE_TEXTURES
#include "scene_trace.glsl"
#ifdef BL_VOXEL_COVERAGE
#include "voxel_alpha.glsl"
#endif

float bounceConeSurface(vec3 origin, vec3 direction) {
    Hit h;
    // The flag with per-ray data in the condition (docs/notes/soak.md).
    if (voxelLighting.params.z == 0u || any(isnan(origin))) return 0.0;
    return traceRay(origin, direction, 0.0, 1e30, false, h) ? max(h.t, 1e-6) : 0.0;
}

vec3 blVoxelEmittance(BlVoxelFragment f) {
    uint material = uint(f.user0.x + 0.5);
    vec3 albedo = materials[4u * material].rgb;
    float layer = materials[4u * material + 2u].x;
    if (layer >= 0.0) albedo *= textureLod(baseColorTextures, vec3(f.user0.yz, layer), 0.0).rgb;
    Surface s;
    s.baseColor = albedo * (1.0 - materials[4u * material + 1u].w);  // metals send (almost) no diffuse light
    s.roughness = 1.0;
    s.metalness = 0.0;
    s.dielectricF0 = 0.0;  // Lambertian: the light leaves the same way in every direction
    vec3 n = f.normal;
    // The fragment's point lies on the triangle's plane within a voxel of the triangle: start the shadow rays
    // half a voxel above it.
    vec3 p = f.position + n * (0.5 * f.voxelSize);
    rngState = pcg(floatBitsToUint(p.x) ^ pcg(floatBitsToUint(p.y) ^ pcg(floatBitsToUint(p.z) ^ sceneLight.counts.y)));
    float eps = sceneLight.lightWeight.y;
    uint samples = clamp(voxelLighting.params.x, 1u, 64u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < samples; ++i) {
        sum += directLight(p, n, n, s, eps);
        vec3 d = cosineDirection(n);
        Hit h;
        if (any(greaterThan(sceneLight.sky.rgb, vec3(0.0))) && !traceRay(p, d, eps, 1e30, true, h)) sum += s.baseColor * sceneLight.sky.rgb;
    }
    vec3 radiance = sum / float(samples);
    // The bounce flag with per-fragment data in the condition: lavapipe would otherwise compile a variant per draw
    // (docs/notes/soak.md).
    if (voxelLighting.params.y != 0u && f.voxelSize > 0.0) radiance += s.baseColor * blVoxelIndirect(f);
    return radiance;
}
