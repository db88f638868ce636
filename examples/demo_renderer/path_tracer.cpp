#include "path_tracer.h"

#include <cmath>
#include <cstring>


namespace bricklight::render {

namespace {
const char* kAovNames[] = {"combined", "direct", "indirect-diffuse", "albedo", "normal", "depth", "ao"};
static_assert(sizeof(kAovNames) / sizeof(kAovNames[0]) == size_t(Aov::Count), "a name for every AOV");
}  // namespace

const char* aovName(Aov aov) { return aov < Aov::Count ? kAovNames[uint32_t(aov)] : "?"; }

bool aovFromName(const std::string& name, Aov* out) {
    for (uint32_t i = 0; i < uint32_t(Aov::Count); ++i)
        if (name == kAovNames[i]) return *out = Aov(i), true;
    return false;
}

std::unique_ptr<PathTracer> PathTracer::create(rhi::IDevice& device, const scenes::SceneGeometry& scene,
                                               const PathTracerOptions& options, std::string* error) {
    auto fail = [&](const std::string& m) {
        if (error) *error = "path tracer: " + m;
        return std::unique_ptr<PathTracer>();
    };
    if (!std::isfinite(options.aoRange) || options.aoRange < 0.0f)
        return fail("aoRange must be finite and >= 0 (0: a tenth of the scene's diagonal), got " + std::to_string(options.aoRange));
    std::string sceneError;
    if (!checkImageSize(options.width, options.height, &sceneError)) return fail(sceneError);
    // Every AOV's sums, then one row of per-pixel counts of samples cut short (path_trace.comp).
    const uint64_t accumulationBytes = uint64_t(options.width) * options.height * 16 * (uint32_t(Aov::Count) + 1);
    if (!checkStorageRange(device, accumulationBytes,
                           "the path tracer's accumulation at " + std::to_string(options.width) + "x" + std::to_string(options.height),
                           &sceneError))
        return fail(sceneError + ": render a smaller image");
    std::unique_ptr<GpuScene> gpuScene = GpuScene::create(device, scene, &sceneError);
    if (!gpuScene) return fail(sceneError);
    std::unique_ptr<PathTracer> pt(new PathTracer(device));
    pt->options_ = options;
    pt->scene_ = std::move(gpuScene);
    pt->aoRange_ = options.aoRange;
    if (pt->aoRange_ == 0.0f) {
        // The bounds of what is traced (scene.boundsMin/Max are only as fresh as its last computeBounds()).
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const glm::vec3& v : pt->scene_->worldPositions()) lo = glm::min(lo, v), hi = glm::max(hi, v);
        pt->aoRange_ = 0.1f * glm::length(hi - lo);
    }
    rhi::BufferDesc d;
    d.size = accumulationBytes;
    d.debugName = "path tracer accumulation";
    pt->accumulation_ = device.createBuffer(d);
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("render/path_trace.comp");
    if (!sd.blob) return fail("shader render/path_trace.comp is not linked into this program");
    pt->shader_ = device.createShader(sd);
    if (!pt->shader_ || !pt->accumulation_) return fail("the device could not create the path tracer's resources (see its messages)");
    if (!pt->setCamera(scene.camera, error)) return nullptr;
    return pt;
}

PathTracer::~PathTracer() {
    if (accumulation_) device_.destroy(accumulation_);
    if (shader_) device_.destroy(shader_);
}

bool PathTracer::setCamera(const scenes::Camera& camera, std::string* error) {
    std::string why;
    if (!checkCamera(camera, &why)) {
        if (error) *error = "path tracer: " + why;
        return false;
    }
    camera_ = camera;
    samples_ = 0;
    device_.clearBuffer(accumulation_, {}, 0);
    return true;
}

void PathTracer::addSamples(uint32_t samples) {
    const glm::vec3 forward = glm::normalize(camera_.at - camera_.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera_.up));
    const glm::vec3 up = glm::cross(right, forward);
    struct {
        glm::vec4 eye, forward, right, up;
        uint32_t size[4];
    } p{};
    p.eye = glm::vec4(camera_.eye, aoRange_);
    p.forward = glm::vec4(forward, std::tan(glm::radians(camera_.verticalFovDegrees) * 0.5f));
    p.right = glm::vec4(right, float(options_.width) / float(options_.height));
    p.up = glm::vec4(up, 0.0f);
    p.size[0] = options_.width;
    p.size[1] = options_.height;
    p.up.w = options_.pixelJitter ? 1.0f : 0.0f;
    const SceneLightConstants light = scene_->lightConstants(options_.seed, options_.maxBounces);
    while (samples > 0) {
        const uint32_t batch = std::min(samples, std::max(1u, options_.samplesPerDispatch));
        p.size[2] = samples_;
        p.size[3] = batch;
        rhi::DispatchState s;
        s.shader = shader_;
        s.label = "path trace";
        s.bindings.constants.push(rhi::constants(2, p));
        s.bindings.constants.push(rhi::constants(1, light));
        scene_->bind(s.bindings);
        s.bindings.storageBuffers.push({0, accumulation_, {}, rhi::Access::ReadWrite});
        device_.dispatch(s, (options_.width + 7) / 8, (options_.height + 7) / 8, 1);
        samples_ += batch;
        samples -= batch;
    }
}

Image PathTracer::read(Aov aov) {
    Image img;
    img.width = options_.width;
    img.height = options_.height;
    const size_t pixels = size_t(options_.width) * options_.height;
    std::vector<glm::vec4> sums(pixels);
    device_.readBuffer(accumulation_, uint64_t(aov) * pixels * 16, pixels * 16, sums.data());
    img.rgb.resize(pixels * 3);
    for (size_t i = 0; i < pixels; ++i) {
        const float n = sums[i].w > 0.0f ? sums[i].w : 1.0f;
        img.rgb[3 * i] = sums[i].x / n;
        img.rgb[3 * i + 1] = sums[i].y / n;
        img.rgb[3 * i + 2] = sums[i].z / n;
    }
    return img;
}

// Row 7 of the accumulation: per pixel, x samples cut short, y samples left out as non-finite (path_trace.comp).
glm::dvec2 PathTracer::samplesLeftOut() {
    const size_t pixels = size_t(options_.width) * options_.height;
    std::vector<glm::vec4> counts(pixels);
    device_.readBuffer(accumulation_, uint64_t(Aov::Count) * pixels * 16, pixels * 16, counts.data());
    glm::dvec2 total(0.0);
    for (const glm::vec4& c : counts) total += glm::dvec2(c.x, c.y);
    return total;
}

uint64_t PathTracer::samplesCutShort() { return uint64_t(samplesLeftOut().x); }
uint64_t PathTracer::samplesNonFinite() { return uint64_t(samplesLeftOut().y); }

}  // namespace bricklight::render
