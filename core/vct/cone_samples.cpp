// vct::ConeTracer::debugConeSamples and readConeSamples: one pixel's cones recorded sample by sample
// (shaders/vct/cone_samples.comp, through cone_trace.glsl's BL_CONE_TRACE_RECORD hook) and drawn over the view
// (cone_samples_view.comp).
#include <cstring>

#include "bricklight/vct.h"
#include "../common/core_shaders.h"
#include "../common/refusal.h"

namespace bricklight::vct {

namespace {

constexpr uint32_t kRecordedCones = kSpecularCone + 1;
constexpr uint64_t kHeaderBytes = (kRecordedCones + 3) * 4;  // the counts, padded to 16 bytes (cone_samples_layout.glsl)
constexpr uint64_t kRecordBytes = kHeaderBytes + uint64_t(kRecordedCones) * kMaxConeSamples * 3 * 16;

}  // namespace

bool ConeTracer::debugConeSamples(uint32_t x, uint32_t y, rhi::TextureHandle output, Error* error) {
    const bricklight::detail::Refusal fail(error, "cone tracer: cone samples");
    if (!latest_) return fail("nothing traced yet (call dispatch first)", ErrorCode::InvalidState);
    if (x >= width_ || y >= height_)
        return fail("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the tracer's " + std::to_string(width_) + "x" +
                    std::to_string(height_));
    const rhi::TextureDesc* od = device_.describe(output);
    if (!od || od->format != rhi::Format::RGBA8_UNORM || !(od->usage & rhi::TextureUsage::Storage) || od->width != width_ ||
        od->height != height_)
        return fail("the output must be a live RGBA8_UNORM texture with Storage usage of the tracer's size", ErrorCode::WrongFormat);
    const TraceDesc& d = *latest_;
    for (rhi::TextureHandle t : {d.gbuffer.depth, d.gbuffer.normals, d.gbuffer.roughness})
        if (!device_.describe(t)) return fail("an input of the latest dispatch is no longer live");
    if (d.gbuffer.motionVectors && !device_.describe(d.gbuffer.motionVectors)) return fail("an input of the latest dispatch is no longer live");
    if (!coneSampleRecord_) {
        coneSamples_ = shaders::createCoreShader(device_, "vct/cone_samples.comp");
        coneSamplesSdf_ = shaders::createCoreShader(device_, "vct/cone_samples_sdf.comp");
        coneSamplesView_ = shaders::createCoreShader(device_, "vct/cone_samples_view.comp");
        rhi::BufferDesc bd;
        bd.size = kRecordBytes;
        bd.usage = rhi::BufferUsage::ShaderRead | rhi::BufferUsage::ShaderWrite;
        bd.debugName = "vct cone samples";
        coneSampleRecord_ = device_.createBuffer(bd);
        if (!coneSamples_ || !coneSamplesSdf_ || !coneSamplesView_ || !coneSampleRecord_)
            return fail("the device could not create the recording passes", ErrorCode::DeviceFailure);
    }
    struct {
        int32_t pixel[4];
    } probe{{int32_t(x), int32_t(y), d.outputSpecular ? 1 : 0, 0}};
    device_.beginMarker("vct cone samples");
    rhi::DispatchState record;
    record.shader = d.occlusionField ? coneSamplesSdf_ : coneSamples_;
    record.label = "vct record cone samples";
    bindCommon(record.bindings, d);
    bindField(record.bindings, d);
    record.bindings.constants.push(rhi::constants(0, probe));
    record.bindings.storageBuffers.push({0, coneSampleRecord_, {}, rhi::Access::ReadWrite});
    device_.dispatch(record, 1, 1, 1);
    rhi::DispatchState view;
    view.shader = coneSamplesView_;
    view.label = "vct draw cone samples";
    bindCommon(view.bindings, d);
    view.bindings.constants.push(rhi::constants(0, probe));
    view.bindings.readBuffers.push(rhi::ReadBufferBinding{0, coneSampleRecord_, {}});
    view.bindings.storageImages.push(rhi::storageImage(0, output, rhi::Access::Write));
    device_.dispatch(view, (width_ + 7) / 8, (height_ + 7) / 8, 1);
    device_.endMarker();
    return true;
}

std::vector<ConeSample> ConeTracer::readConeSamples() {
    std::vector<ConeSample> samples;
    if (!coneSampleRecord_) return samples;
    std::vector<uint8_t> bytes(kRecordBytes);
    device_.readBuffer(coneSampleRecord_, 0, bytes.size(), bytes.data());
    uint32_t counts[kRecordedCones];
    std::memcpy(counts, bytes.data(), sizeof(counts));
    for (uint32_t cone = 0; cone < kRecordedCones; ++cone)
        for (uint32_t i = 0; i < std::min(counts[cone], kMaxConeSamples); ++i) {
            float v[12];
            std::memcpy(v, bytes.data() + kHeaderBytes + (uint64_t(cone) * kMaxConeSamples + i) * 48, sizeof(v));
            ConeSample s;
            s.position = glm::vec3(v[0], v[1], v[2]);
            s.diameter = v[3];
            s.light = glm::vec3(v[4], v[5], v[6]);
            s.transmittance = v[7];
            s.level = uint32_t(v[8] + 0.5f);
            s.cone = cone;
            samples.push_back(s);
        }
    return samples;
}

}  // namespace bricklight::vct
