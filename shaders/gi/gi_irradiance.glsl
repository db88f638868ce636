// Irradiance SH at a surface point from the two caches: the screen probes around the pixel and the
// world-space brick SH around the point. Needs ProbeInfo/ProbeSH (`probeInfo`, `probeSH`) and the brick
// SH buffer (`giBrickSH`) declared by the including pass.
#ifndef BRICKLIGHT_GI_IRRADIANCE_GLSL
#define BRICKLIGHT_GI_IRRADIANCE_GLSL

// The up to 4 probes of the tiles around the pixel, weighted bilinearly, by how close they are to the
// pixel's plane and how similar their normal is. Returns the total weight (0: no usable probe).
float giScreenProbes(uvec2 pixel, vec3 p, vec3 n, out GiSH result) {
    result = giShZero();
    vec2 f = (vec2(pixel) + 0.5) / 8.0 - 0.5;
    ivec2 t0 = ivec2(floor(f));
    vec2 w2 = f - vec2(t0);
    float distance = length(p - giFrame.camera.xyz);
    float total = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 tile = clamp(t0 + o, ivec2(0), ivec2(giFrame.tiles.xy) - 1);
        uint index = uint(tile.y) * giFrame.tiles.x + uint(tile.x);
        uvec4 info = probeInfo[index];
        if ((info.w & GI_PROBE_VALID) == 0u) continue;
        float covered = probeSH[index * 9u].w;
        if (covered <= 0.0) continue;
        vec3 q = giWorldPosition(giPixelUv(giProbePixel(info)), uintBitsToFloat(info.y), giCamera.inverseViewProjection);
        vec3 m = giProbeNormal(info);
        float plane = abs(dot(q - p, n)) / (0.01 * distance + 1e-6);
        float facing = max(dot(n, m), 0.0);
        vec2 b = mix(1.0 - w2, w2, vec2(o));
        float w = (b.x * b.y + 1e-3) * exp(-plane * plane) * pow(facing, 8.0) * covered;
        if (w <= 1e-6) continue;
        for (int i = 0; i < 9; ++i) result.c[i] += probeSH[index * 9u + uint(i)].rgb * w;
        total += w;
    }
    if (total > 0.0)
        for (int i = 0; i < 9; ++i) result.c[i] /= total;
    return total;
}

// Trilinear over the bricks around p (moved a quarter voxel off the surface) in the finest traced
// cascade that has any; bricks whose centre lies behind the surface are left out (no light from the other
// side of a wall). Returns the total weight (0: none).
float giWorldCache(vec3 p, vec3 n, out GiSH result) {
    result = giShZero();
    for (uint c = giFrame.cascades.x; c <= giFrame.cascades.y; ++c) {
        BlSdfCascade info = blSdfTable.cascades[c];
        if (info.origin.w == 0) continue;
        float size = info.voxelSize.x;
        vec3 local = (p + n * (0.25 * size)) * info.voxelSize.y - 0.5;
        ivec3 cell = ivec3(floor(local));
        vec3 f = local - vec3(cell);
        float total = 0.0;
        for (int k = 0; k < 8; ++k) {
            ivec3 o = ivec3(k & 1, (k >> 1) & 1, k >> 2);
            ivec3 voxel = cell + o;
            uint brick = giBrickOfVoxel(voxel, c);
            if (brick == BL_SDF_UNBUILT) continue;
            vec3 centre = (vec3(voxel) + 0.5) * size;
            if (dot(centre - p, n) < -0.75 * size) continue;
            float weight;
            GiSH s = giLoadBrickSH(brick, weight);
            if (weight <= 0.0) continue;
            vec3 w3 = mix(1.0 - f, f, vec3(o));
            float w = w3.x * w3.y * w3.z * min(weight, 4.0) + 1e-4;
            for (int i = 0; i < 9; ++i) result.c[i] += s.c[i] * w;
            total += w;
        }
        if (total > 0.0) {
            for (int i = 0; i < 9; ++i) result.c[i] /= total;
            return total;
        }
    }
    return 0.0;
}

// Both caches: the screen probes where they exist (they see this view's detail), blended with the world
// cache (stable, and the fallback where probes are missing).
#define GI_WORLD_SHARE 0.3
bool giIrradianceSH(uvec2 pixel, vec3 p, vec3 n, out GiSH result) {
    GiSH screen, world;
    float ws = giScreenProbes(pixel, p, n, screen);
    float ww = giWorldCache(p, n, world);
    if (ws > 0.0 && ww > 0.0) result = giShMix(screen, world, GI_WORLD_SHARE);
    else if (ws > 0.0) result = screen;
    else if (ww > 0.0) result = world;
    else {
        result = giShZero();
        return false;
    }
    return true;
}

#endif
