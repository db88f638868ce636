// The direct light over frames (docs/render.md, "Direct light over frames"): each frame's direct lighting is a
// fresh estimate with RasterOptions::lightSamples emitter samples per pixel; examples/demo_renderer/shaders/
// accumulate_direct.comp keeps a reprojected running mean of them per surface point, which the composite, the
// lit image the GI feeds on and the direct-light AOV read. A still camera converges as if each pixel had
// lightSamples × frames samples; a moving one keeps what reprojects onto the same point.
//
// The host drops or shortens the history where the light itself changed, which the shader cannot see:
//  - a camera cut, or the lights changed (sky, sun, emitters): the mean starts over;
//  - the scene's geometry moved (setScene): shadows move too, so the mean spans at most kMovingSceneFrames.
#include "raster_renderer.h"

#include <cmath>
#include <cstring>

namespace bricklight::render {

namespace {
// The mean's length while geometry moves: long enough to take the grain down by ~2×, short enough that a moving
// shadow trails by a few frames only.
constexpr uint32_t kMovingSceneFrames = 4;
}  // namespace

bool RasterRenderer::createDirectHistory(std::string* error) {
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("render/accumulate_direct.comp");
    accumulateDirect_ = sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
    rhi::BufferDesc bd;
    bd.size = uint64_t(options_.width) * options_.height * 16;
    bd.debugName = "direct lighting, accumulated";
    directMean_ = device_.createBuffer(bd);
    for (int i = 0; i < 2; ++i) {
        bd.debugName = "direct lighting history " + std::to_string(i);
        directHistory_[i] = device_.createBuffer(bd);
        bd.debugName = "direct lighting history points " + std::to_string(i);
        directPoints_[i] = device_.createBuffer(bd);
    }
    if (!accumulateDirect_ || !directMean_ || !directHistory_[0] || !directHistory_[1] || !directPoints_[0] || !directPoints_[1]) {
        if (error) *error = "raster renderer: the device could not create the direct light's history (see its messages)";
        return false;
    }
    return true;
}

void RasterRenderer::destroyDirectHistory() {
    if (accumulateDirect_) device_.destroy(accumulateDirect_);
    for (rhi::BufferHandle b : {directMean_, directHistory_[0], directHistory_[1], directPoints_[0], directPoints_[1]})
        if (b) device_.destroy(b);
}

void RasterRenderer::accumulateDirectLight(const SceneLightConstants& light, bool cut) {
    const bool lightsChanged = !directHistoryValid_ || std::memcmp(&light, &previousLight_, sizeof light) != 0;
    previousLight_ = light;
    uint32_t frames = std::max(options_.directFrames, 1u);
    if (sceneMoved_) frames = std::min(frames, kMovingSceneFrames);
    sceneMoved_ = false;
    const bool keep = directHistoryValid_ && !cut && !lightsChanged && frames > 1;
    const float pixelAngle = 2.0f * std::tan(0.5f * glm::radians(camera_.verticalFovDegrees)) / float(options_.height);
    struct {
        glm::vec4 eye, previousEye;
        uint32_t size[4];
        glm::vec4 pixelAngle;
    } p{glm::vec4(camera_.eye, 1.0f), glm::vec4(previousEye_, 1.0f), {options_.width, options_.height, frames, keep ? 1u : 0u},
        glm::vec4(pixelAngle, 0.0f, 0.0f, 0.0f)};
    const uint32_t read = directParity_, write = directParity_ ^ 1u;
    rhi::DispatchState s;
    s.shader = accumulateDirect_;
    s.label = "accumulate direct light";
    s.bindings.constants.push(rhi::constants(0, p));
    uint8_t slot = 0;
    for (rhi::TextureHandle t : {albedo_, normal_, emission_, position_, motion_}) s.bindings.textures.push({slot++, rhi::wholeTexture(t), point_});
    s.bindings.readBuffers.push({0, direct_, {}});
    s.bindings.readBuffers.push({1, directHistory_[read], {}});
    s.bindings.readBuffers.push({2, directPoints_[read], {}});
    s.bindings.storageBuffers.push({0, directMean_, {}, rhi::Access::Write});
    s.bindings.storageBuffers.push({1, directHistory_[write], {}, rhi::Access::Write});
    s.bindings.storageBuffers.push({2, directPoints_[write], {}, rhi::Access::Write});
    device_.beginMarker("accumulate direct light");
    device_.dispatch(s, (options_.width + 7) / 8, (options_.height + 7) / 8, 1);
    device_.endMarker();
    directParity_ = write;
    directHistoryValid_ = true;
    previousEye_ = camera_.eye;
}

}  // namespace bricklight::render
