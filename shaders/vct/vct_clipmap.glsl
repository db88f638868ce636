// The clip-map's addressing (include/bricklight/vct.h, ClipmapPlacement::toroidalTexel): level L's voxels
// live in z slice range [L × resolution, (L + 1) × resolution) of each volume, a world voxel at its
// coordinates modulo the resolution, so that a level keeps what it still covers while it scrolls.
ivec3 vctTexel(uint level, ivec3 worldVoxel, uint resolution) {
    ivec3 t = worldVoxel & ivec3(int(resolution) - 1);  // a power of two: the positive modulo, also below zero
    return t + ivec3(0, 0, int(level * resolution));
}
