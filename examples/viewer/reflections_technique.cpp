// The reflections panel (docs/reflections.md "Hybrid reflections", docs/render.md "Reflections"): where glossy
// reflections come from — GI's specular alone, or the reflection classifier's screen-space and distance-field rays,
// denoised — and the classifier's counts of the latest frame. The views "reflections", "reflection-tile-class",
// "reflection-rays" and "reflection-counters" show its output and tiles. Registered, not called by the UI code.
#include <imgui.h>

#include "technique_registry.h"
#include "viewer_app.h"

namespace bricklight::viewer {

namespace {

void reflectionsPanel(ViewerApp& app) {
    render::RenderOptions& options = app.settings().render;
    int mode = int(options.reflections);
    const char* modes[] = {"GI's specular", "hybrid: screen-space + SDF rays per tile"};
    const bool sdfGi = options.gi && options.giTechnique == render::GiTechnique::Sdf;
    if (!sdfGi) ImGui::TextDisabled("hybrid reflections need the SDF GI");
    if (ImGui::Combo("reflections", &mode, modes, 2) && (sdfGi || mode == 0)) {
        options.reflections = render::ReflectionMode(mode);
        app.requestRebuild();
    }
    static bool showCounts = false;
    ImGui::Checkbox("show the reflection classifier's counts (waits for the GPU)", &showCounts);
    render::RasterRenderer* renderer = app.renderer();
    reflections::ReflectionClassifier* classifier = renderer ? renderer->reflectionClassifier() : nullptr;
    if (!showCounts || !classifier) return;
    const reflections::ReflectionClassifyCounts c = classifier->readCounts();
    ImGui::Text("tiles: screen-space first %u, checkerboard %u, SDF only %u", c.screenSpaceFirstTiles, c.checkerboardTiles, c.sdfOnlyTiles);
    ImGui::Text("rays: screen-space %u (hits %u, misses %u), SDF %u", c.screenRays, c.screenHits, c.screenMisses, c.sdfRays);
    ImGui::Text("pixels with a ray %u of %u surface pixels (%.1f %%)", c.rayPixels, c.surfacePixels,
                c.surfacePixels ? 100.0 * c.rayPixels / c.surfacePixels : 0.0);
}

}  // namespace

BRICKLIGHT_VIEWER_TECHNIQUE(Technique{"Reflections", "Hybrid reflections: the reflection classifier, screen-space and SDF rays (docs/reflections.md).",
                                      35, reflectionsPanel});

}  // namespace bricklight::viewer
