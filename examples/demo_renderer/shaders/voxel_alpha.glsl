// The coverage of the renderer's alpha-tested materials for voxel cone tracing (blVoxelCoverage,
// bricklight/voxelize.glsl's BL_VOXEL_COVERAGE), included by voxel_emittance.frag and voxel_coverage.frag after
// scene_trace.glsl (with BL_SCENE_TEXTURES): the G-buffer's alpha test (gbuffer.frag), base alpha × the texture
// layer's alpha at level 0 against the cut-off, at the texture coordinates render/voxelize.vert passes in
// user0.yz. The voxelization averages it over 16 points per voxel column, so a card's voxels block the share
// of light its texels cover.
float blVoxelCoverage(BlVoxelFragment f) {
    uint material = uint(f.user0.x + 0.5);
    vec2 alphaTest = materials[4u * material + 3u].xy;  // cut-off (0: opaque), base alpha
    if (alphaTest.x <= 0.0) return 1.0;
    float layer = materials[4u * material + 2u].x;
    float alpha = layer >= 0.0 ? textureLod(baseColorTextures, vec3(f.user0.yz, layer), 0.0).a : 1.0;
    return alpha * alphaTest.y < alphaTest.x ? 0.0 : 1.0;
}
