// Cone tracing through the voxel clip-map (include/bricklight/vct.h), for our GI passes and for an
// application's own shaders (refraction, reflections, probes): bind Clipmap::traceBindings() and call
// blTraceCone. Slots: the textures BL_CONE_TRACE_TEXTURE_BASE and + 1 (default 8 and 9) and the read buffer
// BL_CONE_TRACE_FRAME_SLOT (default 7); define either before the include to move them. Define
// BL_CONE_TRACE_OCCLUSION_ONLY for cones that need only their transmittance (ambient occlusion): the light's
// arithmetic is compiled out and a cone's radiance is zero.
//
// Units: a cone's distances are in finest voxels from its origin unless said otherwise. A cone is a string of
// samples, each as wide as the cone there (sample diameter = t × coneFactor, at least one finest voxel),
// spaced tracingStep × that width; each sample reads the two levels around its width (quadrilinear), at least
// the finest level that holds it with a margin, and is never wider than a third of its distance from the origin
// (blTraceCone says why). Front to back: radiance += T_lagged × emittance × (α_step / α), T ×= 1 − α_step, with
// α_step the share of the voxel's opacity that falls in the step (one crossing's shares add; blTraceCone). The lag (0..2 samples)
// is VXGI's light-leaking control: the light of a sample is weighed by the transmittance that many samples
// back, so a thin wall's far-side light leaks through less with 0 (and a thin lit surface behind a thin wall
// dims less with 2).
#ifndef BRICKLIGHT_CONE_TRACE_GLSL
#define BRICKLIGHT_CONE_TRACE_GLSL

#include "bricklight/bindings.glsl"
#include "bricklight/vct_layout.glsl"

#ifndef BL_CONE_TRACE_TEXTURE_BASE
#define BL_CONE_TRACE_TEXTURE_BASE 8
#endif
#ifndef BL_CONE_TRACE_FRAME_SLOT
#define BL_CONE_TRACE_FRAME_SLOT 7
#endif

#ifndef BL_VCT_FRAME_DECLARED  // bricklight/voxelize.glsl declares the same block (slot 7)
#define BL_VCT_FRAME_DECLARED
BL_VCT_FRAME_BLOCK(BL_CONE_TRACE_FRAME_SLOT);
#endif
// The clip-map's atlas (vct_layout.glsl) through two views: opacity along x, y, z (rgb, RGBA8_UNORM) and emittance
// radiance (RGB9E5_FLOAT) of the direction regions (+X, +Y, +Z, −X, −Y, −Z; one region when isotropic). The sampler
// repeats in y; x and z have border columns and slices (Clipmap::traceBindings).
BL_TEXTURE(BL_CONE_TRACE_TEXTURE_BASE) uniform sampler3D blVctOpacityVolume;
BL_TEXTURE(BL_CONE_TRACE_TEXTURE_BASE + 1) uniform sampler3D blVctEmittanceVolume;

struct BlCone {
    vec3 origin;              // world space
    vec3 direction;           // unit
    float coneFactor;         // sample diameter / distance = 2 tan(half angle)
    float firstSampleT;       // finest voxels from the origin to the first sample
    float maxDistance;        // world units; 0: until the cone leaves the clip-map or is opaque
    float tracingStep;        // sample spacing / sample diameter (0.25..1)
    float opacityCorrection;  // scales the share of a voxel's opacity each step takes (1: as voxelized)
    uint lightLeakLag;        // 0..2 samples the transmittance lags
    float ambientRange;       // world units: `ambient` is the transmittance at this distance
    // World units from the origin to the first surface along the axis, from an exact source (a ray through the
    // distance field, bricklight/trace.glsl): the cone's samples count only in front of it, and the cone ends
    // there with the light the surface's finest voxels send back along it — so it cannot gather light from
    // behind a wall thinner than its voxels. 0: unknown (the voxels' opacity alone).
    float surfaceDistance;
    // The plane of the surface the cone leaves: its unit normal and the world distance from the origin back to it
    // (a zero normal: none, e.g. a cone from a point in the air). Samples read narrow enough to stay in front of it.
    vec3 planeNormal;
    float planeDistance;
};

struct BlConeResult {
    vec3 radiance;       // the light the cone gathers (radiance arriving along it, averaged over its width)
    float ambient;       // the transmittance at ambientRange (1: open)
    float finalOpacity;  // 1 − the transmittance where the cone stopped
    uint sampleCount;
};

BlCone blDefaultCone(vec3 origin, vec3 direction, float coneFactor) {
    BlCone c;
    c.origin = origin;
    c.direction = direction;
    c.coneFactor = coneFactor;
    c.firstSampleT = 1.0;
    c.maxDistance = 0.0;
    c.tracingStep = 0.5;
    c.opacityCorrection = 1.0;
    c.lightLeakLag = 0u;
    c.ambientRange = 0.0;
    c.surfaceDistance = 0.0;
    c.planeNormal = vec3(0.0);
    c.planeDistance = 0.0;
    return c;
}

// The cone factor of a cone of full angle `angle` (radians).
float blConeFactor(float angle) { return 2.0 * tan(0.5 * angle); }

// 2^e as a float, for −126 ≤ e ≤ 127: built from its exponent bits, exact — without the integer-to-float conversions
// and reciprocals of float(1u << level) and a division by it, which many GPUs run on slower units than arithmetic.
float blVctPow2(int e) { return uintBitsToFloat(uint(e + 127) << 23u); }

// Where a level's voxels hold a point (finest-voxel coordinates), as texture coordinates of the atlas's opacity
// region, except x: texels from the region's first column. Levels ≥ the level count are the coarsest level's mips
// (vct_layout.glsl), which cover what it covers.
vec3 blVctLevelUvw(uint level, vec3 pFinest, float resolution, uint levels) {
    vec3 p = pFinest * blVctPow2(-int(level));  // the level's voxel coordinates
    float slices = float(vctTracedSlices(levels, uint(resolution)));
    if (level < levels) {
        // Toroidal in x and z onto the border column and slice; y wraps in the sampler.
        vec2 xz = p.xz - resolution * floor(p.xz / resolution);
        return vec3(1.0 + xz.x, p.y / resolution, (float(level) * (resolution + 2.0) + 1.0 + xz.y) / slices);
    }
    uint mip = level - (levels - 1u);
    vec3 box = vec3(vctMipBoxOffset(mip, levels, uint(resolution)));
    vec3 t = box + 1.0 + p - vec3(blVctFrame.origin[levels - 1u].xyz >> int(mip));  // the box's first texel is the border
    return vec3(1.0 + t.x, t.y / resolution, t.z / slices);
}


// A level's (or mip's) volumes at a point (finest-voxel coordinates): opacity in w, emittance towards −dir in xyz.
vec4 blVctSampleLevel(uint level, vec3 pFinest, vec3 dir, float resolution, uint levels) {
    vec3 uvw = blVctLevelUvw(level, pFinest, resolution, levels);
    // Opacity along the cone and the light the faces facing back along it send, each axis weighted by the
    // direction's component on it: the share of the voxel's silhouette that face makes (VXGI's weighting). A
    // wall seen at an angle blocks and sends less per voxel, and the cone crosses more of its voxels.
    vec3 w = abs(dir);
#ifdef BL_CONE_TRACE_OCCLUSION_ONLY
    const uint directions = 0u;  // the cones carry no light: the light's arithmetic is compiled out
#else
    uint directions = blVctFrame.params.z;  // 0: no emittance (opacity only), 1: isotropic, 6: six directions
#endif
    // x in the atlas: the opacity region's coordinate, and each region a 1 / regions step further.
    float step = 1.0 / float(vctRegions(directions));
    uvw.x *= step / (resolution + 2.0);
    vec3 axes = textureLod(blVctOpacityVolume, uvw, 0.0).rgb;
    // Where nothing blocks, nothing sends light: a voxel's light is stored premultiplied by the share of it its
    // surfaces block (resolve_light.comp; the downsampling keeps that), so the three emittance reads would give
    // zero — or, where a share below half an 8-bit step rounded every axis's opacity to zero, a fraction of a
    // percent of the surfaces' radiance. Most samples of a cone lie in empty space: this skips three of four reads.
    if (directions == 0u || all(equal(axes, vec3(0.0)))) return vec4(0.0, 0.0, 0.0, min(dot(w, axes), 1.0));
    // The faces that look back along the cone: −X (region 4) for a cone going +x, +X (region 1) otherwise.
    vec3 faces = directions == 1u ? vec3(1.0) : mix(vec3(1.0, 2.0, 3.0), vec3(4.0, 5.0, 6.0), greaterThan(dir, vec3(0.0)));
    vec3 ex = textureLod(blVctEmittanceVolume, vec3(uvw.x + faces.x * step, uvw.yz), 0.0).rgb;
    vec3 ey = textureLod(blVctEmittanceVolume, vec3(uvw.x + faces.y * step, uvw.yz), 0.0).rgb;
    vec3 ez = textureLod(blVctEmittanceVolume, vec3(uvw.x + faces.z * step, uvw.yz), 0.0).rgb;
    // Where the weighted opacities sum past 1 (a corner, a solid voxel seen diagonally) the opacity saturates; the
    // light is scaled with it, so that a sample's light per unit of opacity — the surfaces' radiance — stays as it
    // is (unscaled, a diagonal cone into a corner read up to √3 times the walls' radiance).
    float opacity = dot(w, axes);
    vec3 light = w.x * ex + w.y * ey + w.z * ez;
    return opacity > 1.0 ? vec4(light / opacity, 1.0) : vec4(light, opacity);
}

// The finest level ≥ `level` that holds the point (finest-voxel coordinates) with `marginFinest` finest voxels and one
// of the level's own to spare; the level count if none does. `boxLevel`, `boxLo` and `boxHi` keep the region of the
// level last tested, in finest voxels (boxLevel ≥ the level count: none yet), so that a cone's samples read the
// buffer's origins only where the cone changes level — a few times a cone, not at every sample.
uint blVctHoldingLevelOfCone(uint level, vec3 pFinest, float marginFinest, uint levels, float resolution,
                             inout uint boxLevel, inout vec3 boxLo, inout vec3 boxHi) {
    for (; level < levels; ++level) {
        float scale = blVctPow2(int(level));
        if (level != boxLevel) {
            boxLevel = level;
            boxLo = vec3(blVctFrame.origin[level].xyz) * scale;
            boxHi = boxLo + resolution * scale;
        }
        float m = marginFinest + scale;
        if (all(greaterThanEqual(pFinest, boxLo + m)) && all(lessThanEqual(pFinest, boxHi - m))) break;
    }
    return level;
}

// The same for one point.
uint blVctHoldingLevel(uint level, vec3 pFinest, float marginFinest, uint levels, float resolution) {
    uint boxLevel = levels;
    vec3 boxLo = vec3(0.0), boxHi = vec3(0.0);
    return blVctHoldingLevelOfCone(level, pFinest, marginFinest, levels, resolution, boxLevel, boxLo, boxHi);
}

// The light a surface at `position` (world; e.g. where a ray met it) sends back along −`direction`, as its finest
// voxels hold it: sampled half a finest voxel in front of it, divided by the opacity there. `known` is false
// outside the clip-map and where the voxels hold (almost) no surface.
vec3 blVctSurfaceRadiance(vec3 position, vec3 direction, out bool known) {
    float resolution = float(blVctFrame.params.x);
    uint levels = blVctFrame.params.y;
    vec3 p = position / blVctFrame.scales.x - 0.5 * direction;
    uint level = blVctHoldingLevel(0u, p, 1.0, levels, resolution);
    known = level < levels;
    if (!known) return vec3(0.0);
    vec4 s = blVctSampleLevel(level, p, direction, resolution, levels);
    known = s.w > 0.05;
    return s.rgb / max(s.w, 0.25);
}

BlConeResult blTraceCone(BlCone cone) {
    BlConeResult r;
    r.radiance = vec3(0.0);
    r.ambient = -1.0;
    r.sampleCount = 0u;
    float finest = blVctFrame.scales.x;
    float resolution = float(blVctFrame.params.x);
    uint levels = blVctFrame.params.y;
    uint top = levels - 1u + blVctFrame.flags.y;  // the coarsest level's last mip
    vec3 origin = cone.origin / finest;
    float maxT = cone.maxDistance > 0.0 ? cone.maxDistance / finest : 1.0e30;
    float rangeT = cone.ambientRange / finest;
    float exponent = clamp(cone.tracingStep, 0.05, 1.0) * max(cone.opacityCorrection, 0.0);
    uint lag = min(cone.lightLeakLag, 2u);
    float transmittance = 1.0, lag1 = 1.0, lag2 = 1.0;  // now, one and two samples back
    // The crossing the samples are in: the transmittance before it, its opacity shares so far, where it began.
    float crossingBase = 1.0, crossingShare = 0.0, crossingPeak = 0.0, crossingLast = 0.0;
    float t = max(cone.firstSampleT, 0.0);
    float surfaceT = cone.surfaceDistance > 0.0 ? cone.surfaceDistance / finest : 1.0e30;
    bool hasPlane = dot(cone.planeNormal, cone.planeNormal) > 0.0;
    float planeT = hasPlane ? cone.planeDistance / finest : 1.0e30;
    float planeCos = hasPlane ? max(dot(cone.direction, cone.planeNormal), 0.0) : 0.0;
    uint boxLevel = levels;  // the level whose region boxLo..boxHi hold (blVctHoldingLevelOfCone)
    vec3 boxLo = vec3(0.0), boxHi = vec3(0.0);
    for (int i = 0; i < 256; ++i) {
        // The sample's diameter in finest voxels. Before the surface the axis met (surfaceDistance) samples narrow
        // so as to end in front of it: a sample that reached past it would average in what lies behind the wall
        // (the next room's light) at the coarse level its width asks for.
        // Nor wider than a third of the way back to the origin: a sample blends the two levels around its width, and
        // the coarser one's trilinear read reaches 1.5 of its voxels (three sample widths) behind the sample. A wider
        // sample reads the surface the cone leaves and what lies behind it, whose light faces away: it took their
        // opacity without their light (a cone of factor 1.1 in a closed emissive box gathered 0.39 of its radiance).
        // Wide cones so trace a narrower core near their origin; the diffuse cones' turn each frame covers the rest.
        float width = max(min(t * cone.coneFactor, t / 3.0), 1.0);  // the cone's, where the sample is
        float size = max(min(width, 0.25 * (surfaceT - t)), 1.0);
        // Nor, for the same reason, wider than a third of its height above the plane of the surface it leaves (the
        // cone still steps as wide as it is): a grazing cone's reads reached below that plane into the voxels of the
        // surface's other side — a two-sided floor lit by the sky from below sent that light back up (docs/vct.md).
        size = max(min(size, (planeT + t * planeCos) / 3.0), 1.0);
        if (surfaceT - t < 1.0) {
            bool known;
            vec3 light = blVctSurfaceRadiance((origin + cone.direction * surfaceT) * finest, cone.direction, known);
            float lagged = lag == 0u ? transmittance : (lag == 1u ? lag1 : lag2);
            r.radiance += lagged * light;
#ifdef BL_CONE_TRACE_RECORD  // a debug pass's hook: (world position, world diameter, level (255: the surface read), T, light added)
            BL_CONE_TRACE_RECORD((origin + cone.direction * surfaceT) * finest, finest, 255u, transmittance, lagged * light);
#endif
            if (r.ambient < 0.0 && surfaceT < rangeT) r.ambient = 0.0;
            transmittance = 0.0;
            break;
        }
        vec3 p = origin + cone.direction * t;
        // Wider than the coarsest level's voxels: its mips, which cover the same region.
        float fLevel = min(log2(size), float(top));
        uint level = blVctHoldingLevelOfCone(min(uint(fLevel), levels - 1u), p, 0.5 * size, levels, resolution, boxLevel, boxLo, boxHi);
        if (level >= levels) break;  // left the clip-map
        if (level == levels - 1u) level = max(level, uint(fLevel));
        float f = max(fLevel - float(level), 0.0);
        vec4 s = blVctSampleLevel(level, p, cone.direction, resolution, levels);
        if (f > 0.0 && level < top) s = mix(s, blVctSampleLevel(level + 1u, p, cone.direction, resolution, levels), f);
        float alpha = clamp(s.w, 0.0, 1.0);
        // The cone steps as its width says, but never more than half the way to the surface; the opacity is
        // corrected to the step over the (narrower) sample's size.
        float step = max(min(width * cone.tracingStep, max(0.5 * (surfaceT - t), size * cone.tracingStep)), 0.25);
        float stepExponent = exponent * step / max(size * cone.tracingStep, 0.25);
        // A voxel's opacity is the share of its cross-section its surfaces cover, wherever in the voxel they lie. The
        // trilinear reads spread it over two voxels' length, and consecutive samples through one voxel see the same
        // surfaces: each step holds the share alpha × step / size of them, and the shares of one crossing add (a
        // surface lies in exactly one step), so an opaque wall ends the cone. Compounded as independent layers
        // (Beer), 15–25 % of the light passed through the walls of a closed box. Samples after empty space, or where
        // the opacity rises again after falling below half its peak, meet other surfaces: their transmittances
        // multiply. (A fixed window of two sample widths split a wall crossed at an angle, whose trilinear spread is
        // longer along the cone, into two crossings that compounded: 25 % of a cone passed a closed box's floor.)
        bool rising = alpha > crossingLast * 1.25 + 0.01;
        if (alpha < 0.01 || (rising && crossingLast < 0.5 * crossingPeak)) {
            crossingBase = transmittance;
            crossingShare = 0.0;
            crossingPeak = 0.0;
        }
        crossingPeak = max(crossingPeak, alpha);
        crossingLast = alpha;
        crossingShare += alpha * stepExponent;
        float after = crossingBase * max(1.0 - crossingShare, 0.0);
        float alphaStep = transmittance > 0.0 ? clamp(1.0 - after / transmittance, 0.0, 1.0) : 1.0;
        float lagged = lag == 0u ? transmittance : (lag == 1u ? lag1 : lag2);
        vec3 light = lagged * s.rgb * (alpha > 1.0e-4 ? alphaStep / alpha : stepExponent);
        r.radiance += light;
#ifdef BL_CONE_TRACE_RECORD
        BL_CONE_TRACE_RECORD(p * finest, size * finest, level, transmittance, light);
#endif
        float before = transmittance;
        lag2 = lag1;
        lag1 = transmittance;
        transmittance *= 1.0 - alphaStep;
        if (r.ambient < 0.0 && t + step >= rangeT) r.ambient = mix(before, transmittance, clamp((rangeT - t) / step, 0.0, 1.0));
        t += step;
        ++r.sampleCount;
        if (transmittance < 1.0e-3 || t > maxT) break;
    }
    if (r.ambient < 0.0) r.ambient = transmittance;
    r.finalOpacity = 1.0 - transmittance;
    return r;
}

#endif
