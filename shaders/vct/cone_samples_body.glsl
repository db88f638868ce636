// Records the samples of one pixel's cones (vct::ConeTracer::debugConeSamples): the diffuse cones of this frame's
// turn and the specular cone, traced as trace_diffuse / trace_specular trace them, each sample written by
// cone_trace.glsl's BL_CONE_TRACE_RECORD hook. One thread per diffuse cone; thread 0 traces the specular one too.
// Included by cone_samples.comp and cone_samples_sdf.comp (which defines VCT_SDF_OCCLUSION).
#include "cone_samples_layout.glsl"
uint recordingCone;
void recordConeSample(vec3 position, float diameter, uint level, float transmittance, vec3 light);
#define BL_CONE_TRACE_RECORD recordConeSample
#include "trace_common.glsl"
layout(local_size_x = 64) in;
BL_CONSTANTS(0) uniform Probe {
    ivec4 pixel;  // xy: the pixel whose cones are recorded; z: 1 to trace the specular cone
} probe;
BL_STORAGE_BUFFER(0) ConeSamples { VCT_CONE_SAMPLES_BODY } record;

void recordConeSample(vec3 position, float diameter, uint level, float transmittance, vec3 light) {
    uint i = record.coneSampleCounts[recordingCone];
    if (i >= VCT_MAX_CONE_SAMPLES) return;
    record.coneSampleCounts[recordingCone] = i + 1u;
    uint base = (recordingCone * VCT_MAX_CONE_SAMPLES + i) * 3u;
    record.coneSamples[base] = vec4(position, diameter);
    record.coneSamples[base + 1u] = vec4(light, transmittance);
    record.coneSamples[base + 2u] = vec4(float(level), float(recordingCone), 0.0, 0.0);
}

void main() {
    uint k = gl_LocalInvocationID.x;
    if (k < VCT_RECORDED_CONES) record.coneSampleCounts[k] = 0u;
    memoryBarrierBuffer();
    barrier();
    ivec2 pixel = clamp(probe.pixel.xy, ivec2(0), ivec2(trace.size.xy) - 1);
    float depth = texelFetch(gDepth, pixel, 0).r;
    if (isSky(depth)) return;
    vec3 position = worldPosition(pixel, depth);
    vec3 normal = surfaceNormal(pixel);
    uint cones = diffuseConeCount();
    recordingCone = k;
    if (k < cones) blTraceCone(diffuseCone(k, cones, position, normal, uintBitsToFloat(trace.sparseOffset.w), diffuseFrame(position, normal)));
    if (k == 0u && probe.pixel.z != 0) {
        recordingCone = 32u;
        blTraceCone(specularCone(pixel, position, normal));
    }
}
