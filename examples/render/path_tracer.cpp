#include "path_tracer.h"

#include <cmath>
#include <cstring>

#include "bvh.h"

namespace bricklight::render {

namespace {
const char* kAovNames[] = {"combined", "direct", "indirect-diffuse", "albedo", "normal", "depth"};
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
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
    if (!options.width || !options.height || options.width > 16384 || options.height > 16384)
        return fail("image size " + std::to_string(options.width) + "x" + std::to_string(options.height) + " is out of range");
    // World triangles and materials (one per mesh).
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> materialOf;
    for (const auto& inst : scene.instances) {
        if (inst.mesh >= scene.meshes.size()) return fail("an instance names mesh " + std::to_string(inst.mesh) + ", which does not exist");
        const auto& m = scene.meshes[inst.mesh];
        for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = m.indices[i + size_t(k)];
                if (3 * size_t(v) + 2 >= m.positions.size())
                    return fail("mesh '" + m.name + "': index " + std::to_string(v) + " is out of range");
                glm::vec3 p = glm::vec3(inst.transform * glm::vec4(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2], 1.0f));
                if (!finite(p)) return fail("mesh '" + m.name + "': vertex " + std::to_string(v) + " is not finite");
                positions.push_back(p);
            }
            materialOf.push_back(inst.mesh);
        }
    }
    if (positions.empty()) return fail("the scene has no triangles");
    for (const auto& m : scene.meshes)
        if (!finite(m.albedo) || !finite(m.emission) || glm::any(glm::lessThan(m.albedo, glm::vec3(0.0f))) ||
            glm::any(glm::lessThan(m.emission, glm::vec3(0.0f))) || glm::any(glm::greaterThan(m.albedo, glm::vec3(1.0f))))
            return fail("mesh '" + m.name + "': albedo must be in [0, 1] and emission >= 0");
    const scenes::Environment& env = scene.environment;
    if (!finite(env.skyRadiance) || !finite(env.sunIrradiance) || !finite(env.sunDirection) ||
        glm::any(glm::lessThan(env.skyRadiance, glm::vec3(0.0f))) || glm::any(glm::lessThan(env.sunIrradiance, glm::vec3(0.0f))))
        return fail("the environment's sky and sun must be finite and non-negative");

    Bvh bvh = buildBvh(positions);
    const uint32_t n = uint32_t(positions.size() / 3);
    std::vector<glm::vec4> tris(3 * size_t(n));
    std::vector<glm::vec4> lights;
    float total = 0.0f;
    for (uint32_t slot = 0; slot < n; ++slot) {
        const uint32_t t = bvh.order[slot];
        const uint32_t material = materialOf[t];
        float bits;
        std::memcpy(&bits, &material, 4);
        tris[3 * slot] = glm::vec4(positions[3 * t], bits);
        tris[3 * slot + 1] = glm::vec4(positions[3 * t + 1], 0.0f);
        tris[3 * slot + 2] = glm::vec4(positions[3 * t + 2], 0.0f);
        const glm::vec3 e = scene.meshes[material].emission;
        const float area = 0.5f * glm::length(glm::cross(positions[3 * t + 1] - positions[3 * t], positions[3 * t + 2] - positions[3 * t]));
        const float weight = area * (0.2126f * e.r + 0.7152f * e.g + 0.0722f * e.b);
        if (weight > 0.0f) {
            total += weight;
            float slotBits;
            std::memcpy(&slotBits, &slot, 4);
            lights.push_back(glm::vec4(slotBits, area, total, weight));
        }
    }
    std::vector<glm::vec4> materials;
    for (const auto& m : scene.meshes) {
        materials.push_back(glm::vec4(m.albedo, m.roughness));
        materials.push_back(glm::vec4(m.emission, m.metalness));
    }
    if (lights.empty()) lights.push_back(glm::vec4(0.0f));  // a buffer is never empty

    std::unique_ptr<PathTracer> pt(new PathTracer(device));
    pt->options_ = options;
    pt->environment_ = env;
    pt->environment_.sunDirection = glm::length(env.sunDirection) > 0.0f ? glm::normalize(env.sunDirection) : glm::vec3(0, 1, 0);
    pt->triangles_ = n;
    pt->lightCount_ = total > 0.0f ? uint32_t(lights.size()) : 0u;
    pt->lightWeight_ = total;
    pt->epsilon_ = 1e-5f * std::max(1.0f, glm::length(bvh.nodes[0].max - bvh.nodes[0].min));
    auto buffer = [&](const char* name, const void* data, uint64_t bytes, uint32_t usage) {
        rhi::BufferDesc d;
        d.size = bytes;
        d.usage = usage;
        d.debugName = std::string("path tracer ") + name;
        return device.createBuffer(d, data);
    };
    using namespace rhi::BufferUsage;
    pt->triangleBuffer_ = buffer("triangles", tris.data(), tris.size() * 16, ShaderRead);
    pt->nodeBuffer_ = buffer("bvh", bvh.nodes.data(), bvh.nodes.size() * sizeof(BvhNode), ShaderRead);
    pt->materialBuffer_ = buffer("materials", materials.data(), materials.size() * 16, ShaderRead);
    pt->lightBuffer_ = buffer("lights", lights.data(), lights.size() * 16, ShaderRead);
    pt->accumulation_ = buffer("accumulation", nullptr, uint64_t(options.width) * options.height * 16 * uint32_t(Aov::Count),
                               ShaderRead | ShaderWrite);
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("render/path_trace.comp");
    if (!sd.blob) return fail("shader render/path_trace.comp is not linked into this program");
    pt->shader_ = device.createShader(sd);
    if (!pt->shader_ || !pt->triangleBuffer_ || !pt->nodeBuffer_ || !pt->materialBuffer_ || !pt->lightBuffer_ || !pt->accumulation_)
        return fail("the device could not create the path tracer's resources (see its messages)");
    if (bvh.depth > 48) return fail("the BVH is " + std::to_string(bvh.depth) + " levels deep (the traversal stack holds 48)");
    if (!pt->setCamera(scene.camera, error)) return nullptr;
    return pt;
}

PathTracer::~PathTracer() {
    for (rhi::BufferHandle b : {triangleBuffer_, nodeBuffer_, materialBuffer_, lightBuffer_, accumulation_})
        if (b) device_.destroy(b);
    if (shader_) device_.destroy(shader_);
}

bool PathTracer::setCamera(const scenes::Camera& camera, std::string* error) {
    const glm::vec3 forward = camera.at - camera.eye;
    if (!finite(camera.eye) || !finite(camera.at) || glm::length(forward) <= 0.0f ||
        glm::length(glm::cross(forward, camera.up)) <= 0.0f || !(camera.verticalFovDegrees > 0.0f && camera.verticalFovDegrees < 180.0f)) {
        if (error) *error = "path tracer: the camera needs eye != at, an up vector not along the view, and a field of view in (0, 180)";
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
        glm::vec4 eye, forward, right, up, sky, sunDirection, sunIrradiance;
        uint32_t size[4];
        uint32_t counts[4];
        glm::vec4 lightWeight;
    } p{};
    p.eye = glm::vec4(camera_.eye, epsilon_);
    p.forward = glm::vec4(forward, std::tan(glm::radians(camera_.verticalFovDegrees) * 0.5f));
    p.right = glm::vec4(right, float(options_.width) / float(options_.height));
    p.up = glm::vec4(up, 0.0f);
    p.sky = glm::vec4(environment_.skyRadiance, 0.0f);
    p.sunDirection = glm::vec4(environment_.sunDirection, 0.0f);
    p.sunIrradiance = glm::vec4(environment_.sunIrradiance, 0.0f);
    p.size[0] = options_.width;
    p.size[1] = options_.height;
    p.counts[0] = lightCount_;
    p.counts[1] = options_.seed;
    p.counts[2] = options_.maxBounces;
    p.lightWeight = glm::vec4(lightWeight_, 0, 0, 0);
    while (samples > 0) {
        const uint32_t batch = std::min(samples, std::max(1u, options_.samplesPerDispatch));
        p.size[2] = samples_;
        p.size[3] = batch;
        rhi::DispatchState s;
        s.shader = shader_;
        s.label = "path trace";
        s.bindings.constants.push(rhi::constants(0, p));
        s.bindings.readBuffers.push({0, triangleBuffer_, {}});
        s.bindings.readBuffers.push({1, nodeBuffer_, {}});
        s.bindings.readBuffers.push({2, materialBuffer_, {}});
        s.bindings.readBuffers.push({3, lightBuffer_, {}});
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

}  // namespace bricklight::render
