// Alpha-tested geometry in the SDF GI (RasterOptions::foliage; docs/gi.md, "Foliage"): the cards are registered in
// the distance field as alpha-tested, the GI context keeps an alpha cache, and each frame, after the field's update
// and before the GI's dispatch, the alpha pass draws the scene's vertex buffer through gi::GiContext::alphaPassState
// with render/alpha_pass.vert (only alpha-tested materials' triangles survive) and render/alpha_pass.frag (the
// G-buffer's alpha test).
#include "raster_renderer.h"

namespace bricklight::render {

bool RasterRenderer::alphaAwareFoliage() const { return options_.foliage == FoliageMode::AlphaAware && scene_->hasAlphaTested(); }

bool RasterRenderer::createAlphaPass(std::string* error) {
    auto shader = [&](const char* name) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader(name);
        return sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
    };
    alphaPassVertex_ = shader("render/alpha_pass.vert");
    alphaPassFragment_ = shader("render/alpha_pass.frag");
    if (alphaPassVertex_ && alphaPassFragment_) return true;
    if (error) *error = "raster renderer: the device could not create the GI's alpha pass shaders";
    return false;
}

void RasterRenderer::runAlphaPass() {
    if (!alphaPassFragment_) return;
    Error why;
    std::optional<rhi::DrawCallState> state = gi_->alphaPassState(alphaPassFragment_, &why);
    if (!state) return;  // reported through the GI's error callback
    state->label = "gi alpha pass";
    state->vertexShader = alphaPassVertex_;
    rhi::DrawArgs args;
    scene_->bindAlphaPass(*state, &args);
    device_.beginMarker("gi alpha pass");
    device_.draw(*state, args);
    device_.endMarker();
}

}  // namespace bricklight::render
