// Job-voxel numbering -> (job, world voxel, cascade): binary search over the jobs' first voxels.
// The including shader declares `jobTable` (BL_SDF_JOB_TABLE_BODY).
#ifndef BRICKLIGHT_SDF_JOB_LOOKUP_GLSL
#define BRICKLIGHT_SDF_JOB_LOOKUP_GLSL
void blSdfJobVoxel(uint index, uint jobCount, out ivec3 worldVoxel, out uint cascade) {
    uint lo = 0u, hi = jobCount - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) >> 1;
        if (uint(jobTable.jobs[2u * mid + 1u].w) <= index) lo = mid; else hi = mid - 1u;
    }
    ivec4 jmin = jobTable.jobs[2u * lo];
    ivec4 jsize = jobTable.jobs[2u * lo + 1u];
    uint local = index - uint(jsize.w);
    uint sx = uint(jsize.x), sy = uint(jsize.y);
    worldVoxel = jmin.xyz + ivec3(local % sx, (local / sx) % sy, local / (sx * sy));
    cascade = uint(jmin.w);
}
#endif
