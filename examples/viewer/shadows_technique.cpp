// The sun's shadows panel (docs/render.md "Shadows", docs/shadows.md): where the sun's visibility comes from —
// BVH rays, cascaded shadow maps, or the maps classified per tile with rays through the distance field (hybrid) —
// the maps' parameters (rebuild the renderer), and the shadow classifier's counts of the latest frame. Registered,
// not called by the UI code.
#include <imgui.h>

#include "technique_registry.h"
#include "viewer_app.h"

namespace bricklight::viewer {

namespace {

void shadowsPanel(ViewerApp& app) {
    render::RenderOptions& options = app.settings().render;
    int mode = int(options.shadows);
    const char* modes[] = {"BVH rays (exact)", "cascaded shadow maps", "hybrid: maps + SDF rays per tile"};
    if (ImGui::Combo("sun visibility", &mode, modes, 3)) {
        options.shadows = render::ShadowMode(mode);
        app.requestRebuild();
    }
    if (options.shadows == render::ShadowMode::Bvh) return;
    int resolution = int(options.sunShadows.resolution);
    if (ImGui::SliderInt("cascade resolution", &resolution, int(render::kMinShadowResolution), 4096, "%d", ImGuiSliderFlags_Logarithmic)) {
        options.sunShadows.resolution = uint32_t(resolution);
        app.requestRebuild();
    }
    int pcf = int(options.sunShadows.pcfRadius);
    if (ImGui::SliderInt("PCF radius", &pcf, 0, int(render::kMaxShadowPcfRadius))) {
        options.sunShadows.pcfRadius = uint32_t(pcf);
        app.requestRebuild();
    }
    if (ImGui::SliderFloat("split lambda", &options.sunShadows.splitLambda, 0.0f, 1.0f, "%.2f")) app.requestRebuild();
    if (options.shadows != render::ShadowMode::Hybrid) return;
    static bool showCounts = false;
    ImGui::Checkbox("show the classifier's counts (waits for the GPU)", &showCounts);
    render::RasterRenderer* renderer = app.renderer();
    shadows::ShadowClassifier* classifier = renderer ? renderer->shadowClassifier() : nullptr;
    if (!showCounts || !classifier) return;
    const shadows::ShadowClassifyCounts c = classifier->readCounts();
    const uint32_t tiles = classifier->tilesX() * classifier->tilesY();
    ImGui::Text("tiles listed %u of %u (cut off %u)", c.listedTiles, tiles, c.cutOffTiles);
    ImGui::Text("pixels traced %u of %u facing the sun (%.1f %%)", c.rayPixels, c.activePixels,
                c.activePixels ? 100.0 * c.rayPixels / c.activePixels : 0.0);
}

}  // namespace

BRICKLIGHT_VIEWER_TECHNIQUE(Technique{"Sun shadows", "Shadow maps, the shadow classifier and hybrid SDF shadows (docs/shadows.md).", 30,
                                      shadowsPanel});

}  // namespace bricklight::viewer
