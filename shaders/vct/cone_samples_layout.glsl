// The record of one pixel's cones (vct::ConeTracer::debugConeSamples; vct::ConeSample on the CPU): per cone a
// count, then up to VCT_MAX_CONE_SAMPLES samples of three vec4 each — (world position, world diameter),
// (light the sample added, transmittance before it), (level (255: the surface the distance field met), cone, 0, 0).
// Cones 0..31 are the diffuse ones, cone 32 the specular one.
#define VCT_RECORDED_CONES 33u
#define VCT_MAX_CONE_SAMPLES 64u
#define VCT_CONE_SAMPLES_BODY uint coneSampleCounts[VCT_RECORDED_CONES + 3u]; vec4 coneSamples[];
