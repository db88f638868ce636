// The GI benchmarks' camera and G-buffer (bench_common.h).
#include <array>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_common.h"

namespace bricklight::bench {

BenchCamera cameraAt(const scenes::Camera& c, float yawDegrees, float aspect, float size) {
    BenchCamera k;
    const glm::vec3 forward = c.at - c.eye;
    const glm::vec3 turned = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(yawDegrees), glm::vec3(0, 1, 0)) * glm::vec4(forward, 0.0f));
    k.eye = c.eye;
    k.view = glm::lookAtRH(c.eye, c.eye + turned, c.up);
    k.projection = glm::perspectiveRH_ZO(glm::radians(c.verticalFovDegrees), aspect, 0.001f * size, 8.0f * size);
    k.projection[1][1] = -k.projection[1][1];  // NDC y = -1 at the top row
    return k;
}

bool BenchGBuffer::create(rhi::IDevice& device, uint32_t width, uint32_t height) {
    auto target = [&](rhi::Format f, const char* name) {
        rhi::TextureDesc d;
        d.format = f;
        d.width = width;
        d.height = height;
        d.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage;
        d.debugName = name;
        return device.createTexture(d);
    };
    depth = target(rhi::Format::R32_FLOAT, "bench depth");
    normals = target(rhi::Format::RGBA16_FLOAT, "bench normals");
    motion = target(rhi::Format::RG16_FLOAT, "bench motion");
    lit = target(rhi::Format::RGBA16_FLOAT, "bench lit");
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("bench/sdf_gbuffer.comp");
    shader = sd.blob ? device.createShader(sd) : rhi::ShaderHandle{};
    return depth && normals && motion && lit && shader;
}

void BenchGBuffer::destroy(rhi::IDevice& device) {
    for (rhi::TextureHandle h : {depth, normals, motion, lit})
        if (h) device.destroy(h);
    if (shader) device.destroy(shader);
}

void BenchGBuffer::record(rhi::IDevice& device, sdf::SdfScene& scene, const BenchCamera& now, const BenchCamera& previous,
                          uint32_t width, uint32_t height) const {
    struct {
        glm::mat4 viewProjection, inverseViewProjection, previousViewProjection;
        glm::vec4 eye;
        uint32_t size[4];
    } p{now.projection * now.view, glm::inverse(now.projection * now.view), previous.projection * previous.view,
        glm::vec4(now.eye, 0.4f), {width, height, 0, 0}};
    rhi::DispatchState s;
    s.shader = shader;
    s.label = "bench gbuffer";
    s.bindings.constants.push(rhi::constants(0, p));
    const std::array<rhi::TextureHandle, 4> targets{depth, normals, motion, lit};
    for (uint8_t i = 0; i < 4; ++i) {
        rhi::StorageImageBinding b;
        b.slot = i;
        b.view = rhi::textureMip(targets[i], 0);
        b.access = rhi::Access::Write;
        s.bindings.storageImages.push(b);
    }
    scene.traceBindings(s.bindings, {});
    device.beginMarker("bench gbuffer");
    device.dispatch(s, (width + 7) / 8, (height + 7) / 8, 1);
    device.endMarker();
}

}  // namespace bricklight::bench
