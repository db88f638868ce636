// The coverage hook of the coverage tests (voxelize_coverage.frag and .comp): stripes of known coverage, as an
// alpha-tested card's texture would give, read from the fragment's world position or from its user vector
// (the test vertex shader passes the position there, so both must agree).
BL_CONSTANTS(0) uniform Emission { vec4 radiance; } emission;
BL_CONSTANTS(1) uniform Stripes {
    vec4 shape;  // x period (world units), y covered share of each period, z axis (0 x, 1 y), w 1: read user0
    vec4 mode;   // x 0: stripes, 1: NaN, 2: a constant (y) out of [0, 1]
} stripes;

vec3 blVoxelEmittance(BlVoxelFragment f) { return emission.radiance.rgb; }

float blVoxelCoverage(BlVoxelFragment f) {
    if (stripes.mode.x == 1.0) return uintBitsToFloat(0x7fc00000u);
    if (stripes.mode.x == 2.0) return stripes.mode.y;
    vec3 p = stripes.shape.w != 0.0 ? f.user0.xyz : f.position;
    float x = stripes.shape.z == 0.0 ? p.x : p.y;
    return fract(x / stripes.shape.x) < stripes.shape.y ? 1.0 : 0.0;
}
