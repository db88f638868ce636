// The alpha pass (GiContext::alphaPassState, shaders/gi/alpha_pass.geom, include/bricklight/alpha_pass.glsl)
// and the read-back of the alpha cache for tests and tools.
#include "gi_context_impl.h"

namespace bricklight::gi::detail {

std::optional<rhi::DrawCallState> GiContextImpl::alphaPassState(rhi::ShaderHandle fragmentShader, Error* error) {
    auto refuse = [&](ErrorCode code, const std::string& message) -> std::optional<rhi::DrawCallState> {
        fail(code, "alphaPassState: " + message);
        if (error) *error = lastError();
        return std::nullopt;
    };
    if (!(desc_.flags & ContextFlags::AlphaCache))
        return refuse(ErrorCode::InvalidState, "the context keeps no alpha cache (create it with ContextFlags::AlphaCache)");
    if (!sceneAlive()) {
        if (error) *error = lastError();
        return std::nullopt;
    }
    if (!fragmentShader) return refuse(ErrorCode::MissingInput, "no fragment shader (the application's, including bricklight/alpha_pass.glsl)");
    // Every draw until the next dispatch() belongs to one pass: the first clears the counts of the last.
    // Header word 1 tells the next dispatch that the cells are this pass's: it then keeps those of bricks reallocated
    // by the field update before the pass (clear_freed_bricks.comp), which it would otherwise forget.
    if (alphaPassClearedAt_ != frameIndex_ + 1) {
        device_.clearBuffer(alphaCache_, {kAlphaCacheHeaderWords * 4, 0}, 0);
        device_.clearBuffer(alphaCache_, {4, 4}, 1);
        alphaPassClearedAt_ = frameIndex_ + 1;
    }
    rhi::DrawCallState s;
    s.geometryShader = shaders_.alphaPass;
    s.fragmentShader = fragmentShader;
    s.topology = rhi::PrimitiveTopology::TriangleList;
    s.depthTarget.view = rhi::textureMip(alphaRaster_, 0);
    s.depthTarget.load = rhi::LoadOp::DontCare;
    s.viewport = rhi::Viewport{0.0f, 0.0f, float(kAlphaPassResolution), float(kAlphaPassResolution), 0.0f, 1.0f};
    s.raster.cull = rhi::CullMode::None;  // cards are seen from both sides; every triangle counts once per cascade
    s.label = "gi alpha pass";
    scene_.traceBindings(s.bindings);
    storageBuffer(s.bindings, 7, alphaCache_, rhi::Access::Atomic);
    return s;
}

std::vector<float> GiContextImpl::readAlphaCoverage(std::vector<uint32_t>* fragments) {
    if (!(desc_.flags & ContextFlags::AlphaCache)) return {};
    const rhi::BufferDesc* d = device_.describe(alphaCache_);
    if (!d) return {};
    std::vector<uint32_t> words(d->size / 4 - kAlphaCacheHeaderWords);
    device_.readBuffer(alphaCache_, kAlphaCacheHeaderWords * 4, words.size() * 4, words.data());
    std::vector<float> coverage(words.size());
    if (fragments) fragments->resize(words.size());
    for (size_t i = 0; i < words.size(); ++i) {
        const uint32_t total = words[i] & 0xFFFFu, covered = words[i] >> 16;
        coverage[i] = total ? float(covered) / float(total) : -1.0f;
        if (fragments) (*fragments)[i] = total;
    }
    return coverage;
}

}  // namespace bricklight::gi::detail
