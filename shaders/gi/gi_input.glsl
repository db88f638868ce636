// The application's G-buffer read at an internal pixel, in GI's own encoding: what downsample.comp stores
// in the internal depth and surface, for the passes that run beside it (spawn_probes.comp,
// clear_freed_bricks.comp) and so need not wait for it. One display pixel per internal pixel (the one
// under its centre), so depth and normal stay a consistent pair. The including shader declares the
// samplers inputDepth, inputNormals and inputRoughness.
#ifndef BRICKLIGHT_GI_INPUT_GLSL
#define BRICKLIGHT_GI_INPUT_GLSL

ivec2 giInputPixel(uvec2 pixel) {
    return ivec2(min((vec2(pixel) + 0.5) * vec2(giFrame.size.zw) / vec2(giFrame.size.xy), vec2(giFrame.size.zw) - 1.0));
}

// Device depth (sky where the inputs are unusable: NaN, no normal) and the packed normal + perceptual
// roughness (0 where unusable).
void giReadInput(uvec2 pixel, out float depth, out uint surface) {
    ivec2 source = giInputPixel(pixel);
    depth = texelFetch(inputDepth, source, 0).r;
    vec3 n = texelFetch(inputNormals, source, 0).xyz * giFrame.normalScale.xyz + giFrame.normalOffset.xyz;
    float roughness = texelFetch(inputRoughness, source, 0)[giFrame.inputs.x];
    if (giFrame.inputs.y == 0u) roughness = sqrt(max(roughness, 0.0));
    float len = length(n);
    bool usable = giFinite(depth) && giFinite(n) && len > 1e-3 && giFinite(roughness);
    if (!usable) depth = giSkyDepth();
    surface = usable ? giPackSurface(n / len, roughness) : 0u;
}

#endif
