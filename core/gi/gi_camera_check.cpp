// The camera self-check (shaders/gi/camera_check.comp, docs/gi.md "Camera conventions"): every few frames
// 256 pixels of the application's depth are rebuilt into world positions and looked up in the distance
// field; the counts come back without waiting (IDevice::requestReadback). When most rebuilt positions lie
// off every surface twice in a row, the camera the application gave does not match the one that drew the
// depth buffer, and the context warns once, naming the usual causes. A scene never update()d is warned
// about on the spot.
#include "gi_context_impl.h"

namespace bricklight::gi::detail {

namespace {
constexpr uint64_t kCameraCheckInterval = 4;  // frames between checks
constexpr size_t kMaxPendingChecks = 4;       // read-backs in flight (a device that never finishes them stops the check)
constexpr uint32_t kMinDecidableSamples = 64;  // of 256: fewer (sky, unbuilt field) decide nothing
// A correct camera puts none off the surfaces (tests: 0 of 233 in the atrium); the mistakes put 44 % (no
// y-flip), 95 % ([-1, 1] depth) and 100 % (transposed) there.
constexpr float kMaxOffSurfaceFraction = 0.2f;
constexpr uint32_t kBadChecksToWarn = 2;
}  // namespace

void GiContextImpl::checkScene() {
    if (scene_.updateCount() == 0)
        warnOnce(ErrorCode::SceneNotUpdated,
                 "dispatch: the scene '" + scene_.desc().debugName +
                     "' was never update()d, so its field is empty and GI stays black: call scene.update(cameraPosition) "
                     "before dispatch every frame");
}

void GiContextImpl::recordCameraCheck(const DispatchDesc& d) {
    if ((desc_.flags & ContextFlags::NoCameraCheck) || cameraCheck_.warned) return;
    pollCameraCheck();
    if (frameIndex_ % kCameraCheckInterval != 0 || cameraCheck_.pending.size() >= kMaxPendingChecks) return;
    device_.clearBuffer(cameraCheck_.counts, {}, 0);
    rhi::DispatchState s;
    texture(s.bindings, 0, d.gbuffer.depth, point_);
    storageBuffer(s.bindings, 0, cameraCheck_.counts, rhi::Access::ReadWrite);
    addTrace(s.bindings);
    run("camera check", shaders_.cameraCheck, s, 1, 1);
    if (uint64_t ticket = device_.requestReadback(cameraCheck_.counts, 0, 16)) cameraCheck_.pending.push_back(ticket);
}

void GiContextImpl::pollCameraCheck() {
    while (!cameraCheck_.pending.empty()) {
        uint32_t counts[4] = {};
        const rhi::ReadbackStatus status = device_.pollReadback(cameraCheck_.pending.front(), counts);
        if (status == rhi::ReadbackStatus::Pending) return;
        cameraCheck_.pending.pop_front();
        if (status != rhi::ReadbackStatus::Ready) continue;
        const uint32_t onSurface = counts[0], offSurface = counts[1], decidable = onSurface + offSurface;
        cameraCheck_.lastOffSurfaceFraction = decidable ? float(offSurface) / float(decidable) : -1.0f;
        if (decidable < kMinDecidableSamples) continue;
        const bool bad = float(offSurface) > kMaxOffSurfaceFraction * float(decidable);
        cameraCheck_.badInARow = bad ? cameraCheck_.badInARow + 1 : 0;
        if (cameraCheck_.badInARow < kBadChecksToWarn || cameraCheck_.warned) continue;
        cameraCheck_.warned = true;
        warnOnce(ErrorCode::CameraMismatch,
                 "dispatch: " + std::to_string(offSurface) + " of " + std::to_string(decidable) +
                     " positions rebuilt from 'depth' with view/projection lie off every surface of the distance field: "
                     "the camera given does not match the one that drew the depth buffer. Usual causes: the projection "
                     "lacks the y-flip (image row 0 is the top: projection[1][1] = -projection[1][1] after glm::perspective), "
                     "it maps depth to [-1, 1] (use a [0, 1] projection such as glm::perspectiveRH_ZO, and "
                     "ContextFlags::ReversedDepth for reversed Z), the matrices are transposed (GLM column-major), or the "
                     "G-buffer holds geometry the scene does not (ContextFlags::NoCameraCheck turns this check off)");
    }
}

}  // namespace bricklight::gi::detail
