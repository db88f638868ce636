// Irradiance at a surface point from the two caches: the screen probes around the pixel and the
// world-space brick SH around the point. Needs the brick SH buffer (`giBrickSH`) declared by the including
// pass, and for giScreenProbes/giIrradiance ProbeInfo and the probes' irradiance SH (`probeInfo`,
// `probeIrradianceSH`: the probe's SH with the world cache's share blended in, project_probes.comp).
//
// A pixel reads two things from the SH: the diffuse value for its normal and the specular fallback's lobe
// along its reflection. Both are linear in the SH, so each source's coefficients are dotted with the two
// weight sets as they are loaded (GiShReads), instead of summing whole SH per cache and blending them:
// 18 weights and a few sums in registers instead of three 27-float SH, which held the pass's occupancy
// down (it was the largest per-pixel pass at 4K).
#ifndef BRICKLIGHT_GI_IRRADIANCE_GLSL
#define BRICKLIGHT_GI_IRRADIANCE_GLSL

struct GiShReads {
    float diffuse[9];  // giShDiffuseWeights for the normal
    float lobe[9];     // giShLobeWeights for the reflection and roughness
};

// Adds coefficient i of an SH, times w, to the two readings.
void giShRead(GiShReads reads, int i, vec3 coefficient, float w, inout vec3 diffuse, inout vec3 lobe) {
    diffuse += coefficient * (reads.diffuse[i] * w);
    lobe += coefficient * (reads.lobe[i] * w);
}

// The up to 4 probes of the tiles around the pixel, weighted by their distance to the pixel on screen (a squared
// tent reaching 1.5 tiles), by how close they are to the pixel's plane and how similar their normal is. Returns
// the total weight (0: no usable probe). Each probe sits on a pixel jittered anywhere in its tile, so bilinear
// weights between tile centres gave a probe three quarters of a tile away as much weight as one beside the
// pixel: light was spread over twice the distance, and where a wall's light changes steeply towards an edge
// (the corridor's walls near its lit end) the pixels by the edge took the light of probes farther from it.
float giScreenProbes(uvec2 pixel, vec3 p, vec3 n, GiShReads reads, out vec3 diffuse, out vec3 lobe) {
    diffuse = vec3(0.0);
    lobe = vec3(0.0);
    ivec2 t0 = ivec2(floor((vec2(pixel) + 0.5) / float(giProbeTile()) - 0.5));
    float reach = 1.5 * float(giProbeTile());
    float distance = length(p - giFrame.camera.xyz);
    float total = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 tile = clamp(t0 + o, ivec2(0), ivec2(giFrame.tiles.xy) - 1);
        uint index = uint(tile.y) * giFrame.tiles.x + uint(tile.x);
        uvec4 info = probeInfo[index];
        if ((info.w & GI_PROBE_VALID) == 0u) continue;
        float covered = probeIrradianceSH[index * 9u].w;
        if (covered <= 0.0) continue;
        vec3 q = giWorldPosition(giPixelUv(giProbePixel(info)), uintBitsToFloat(info.y), giCamera.inverseViewProjection);
        vec3 m = giProbeNormal(info);
        float plane = abs(dot(q - p, n)) / (0.01 * distance + 1e-6);
        float facing = max(dot(n, m), 0.0);
        float near = max(1.0 - length(vec2(giProbePixel(info)) - vec2(pixel)) / reach, 0.0);
        float w = (near * near + 1e-3) * exp(-plane * plane) * pow(facing, 8.0) * covered;
        if (w <= 1e-6) continue;
        for (int i = 0; i < 9; ++i) giShRead(reads, i, probeIrradianceSH[index * 9u + uint(i)].rgb, w, diffuse, lobe);
        total += w;
    }
    if (total > 0.0) {
        diffuse /= total;
        lobe /= total;
    }
    return total;
}

// The world cache at p read through the pixel's weights. Returns the total weight (0: none).
float giWorldCache(vec3 p, vec3 n, GiShReads reads, out vec3 diffuse, out vec3 lobe) {
    diffuse = vec3(0.0);
    lobe = vec3(0.0);
    uint bricks[8];
    float weights[8];
    float total = giWorldCacheCorners(p, n, bricks, weights);
    if (total <= 0.0) return 0.0;
    for (int i = 0; i < 9; ++i) giShRead(reads, i, giWorldCacheCoefficient(bricks, weights, total, i), 1.0, diffuse, lobe);
    return total;
}

// The pixel's irradiance and specular-fallback lobe: the screen probes around it, whose SH already hold
// the world cache's share (project_probes.comp blends GI_WORLD_SHARE of the world cache at each probe,
// probe_world_sh.comp, into the SH the pixels read), else — no usable probe around the pixel — the world
// cache at the pixel.
// The readings are clamped at 0 (an L2 estimate can ring below it).
bool giIrradiance(uvec2 pixel, vec3 p, vec3 n, GiShReads reads, out vec3 diffuse, out vec3 lobe) {
    if (giScreenProbes(pixel, p, n, reads, diffuse, lobe) <= 0.0 && giWorldCache(p, n, reads, diffuse, lobe) <= 0.0)
        return false;
    diffuse = max(diffuse, vec3(0.0));
    lobe = max(lobe, vec3(0.0));
    return true;
}

#endif
