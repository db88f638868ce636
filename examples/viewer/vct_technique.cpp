// The voxel cone tracing technique's panel (VXGI-class: include/bricklight/vct.h): the technique itself, the
// clip-map (rebuilds the renderer) and the cone tracing (live), and the clip-map's memory. Registered, not
// called by the UI code.
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "technique_registry.h"
#include "viewer_app.h"

namespace bricklight::viewer {

namespace {

void vctPanel(ViewerApp& app) {
    GiSettings& g = app.gi();
    render::RenderOptions& options = app.settings().render;
    bool vxgi = options.gi && options.giTechnique == render::GiTechnique::Vct;
    if (ImGui::Checkbox("GI by voxel cone tracing (instead of the SDF GI)", &vxgi)) {
        options.giTechnique = vxgi ? render::GiTechnique::Vct : render::GiTechnique::Sdf;
        if (vxgi && !options.gi) app.setGiEnabled(true);
        app.requestRebuild();
    }
    if (ImGui::Checkbox("voxel AO (with voxel GI or no GI)", &options.vxao)) app.requestRebuild();
    if (!vxgi && options.gi && ImGui::Checkbox("SDF GI: unseen surfaces lit from a clip-map", &options.giUnseenFromVct)) app.requestRebuild();
    if (!vxgi && !options.vxao) return;
    if (ImGui::Checkbox("cones stop at the distance field's surfaces", &options.vctSdfOcclusion)) app.requestRebuild();

    // Fixed at creation: these rebuild the renderer.
    const char* resolutions[] = {"32", "64", "128", "256"};
    int resolution = std::clamp(int(std::log2(double(g.vctResolution))) - 5, 0, 3);
    if (ImGui::Combo("resolution per level", &resolution, resolutions, 4)) {
        g.vctResolution = 32u << resolution;
        app.requestRebuild();
    }
    int levels = int(g.vctLevels);
    if (ImGui::SliderInt("levels", &levels, int(vct::kMinLevels), int(vct::kMaxLevels))) {
        g.vctLevels = uint32_t(levels);
        app.requestRebuild();
    }
    const char* modes[] = {"none (AO only)", "isotropic", "six directions"};
    int mode = int(g.vctEmittance);
    if (ImGui::Combo("emittance", &mode, modes, 3)) {
        g.vctEmittance = vct::EmittanceMode(mode);
        app.requestRebuild();
    }
    int sparsity = int(g.vctTrace.tracingSparsity);
    if (ImGui::SliderInt("diffuse sparsity", &sparsity, 1, 4)) {
        g.vctTrace.tracingSparsity = uint32_t(sparsity);  // live: the tracer re-creates its sparse targets
    }

    // Live: the next frame's vct::TraceDesc::params.
    ImGui::Separator();
    ImGui::TextUnformatted("cone tracing (live)");
    int cones = int(g.vctTrace.diffuseCones);
    if (ImGui::SliderInt("diffuse cones", &cones, 1, 32)) g.vctTrace.diffuseCones = uint32_t(cones);
    ImGui::SliderFloat("diffuse step", &g.vctTrace.tracingStep, 0.25f, 1.0f, "%.2f");
    ImGui::SliderFloat("specular step", &g.vctTrace.specularTracingStep, 0.25f, 1.0f, "%.2f");
    ImGui::SliderFloat("opacity correction", &g.vctTrace.opacityCorrection, 0.1f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    int lag = int(g.vctTrace.lightLeakLag);
    if (ImGui::SliderInt("light-leak lag (samples)", &lag, 0, 2)) g.vctTrace.lightLeakLag = uint32_t(lag);
    ImGui::SliderFloat("start offset (voxels)", &g.vctTrace.initialOffset, 0.0f, 8.0f, "%.2f");
    ImGui::SliderFloat("temporal weight", &g.vctTrace.temporalWeight, 0.0f, 0.98f, "%.2f");
    ImGui::SliderFloat("specular tangent jitter", &g.vctTrace.specularJitter, 0.0f, 1.0f, "%.2f");
    ImGui::SliderFloat("specular roughness cap", &g.vctTrace.maxSpecularRoughness, 0.0f, 1.0f, "%.2f");

    render::RasterRenderer* r = app.renderer();
    if (!r || !r->clipmap()) return;
    ImGui::Separator();
    const vct::Clipmap& c = *r->clipmap();
    ImGui::Text("finest voxel %.3g, coarsest level %.3g wide", c.placement().voxelSize(0),
                c.placement().voxelSize(c.desc().levels - 1) * float(c.desc().resolution));
    ImGui::Text("rewritten this frame: %zu boxes", c.rewriteBoxes().size());
    ImGui::Text("clip-map memory %.1f MiB", double(c.memoryUse().totalBytes) / (1 << 20));
    // The pixel whose cones the vct-cone-samples view shows (in the renderer's image, not the window's).
    int* probe = g.vctProbePixel;
    const int w = int(r->options().width), h = int(r->options().height);
    if (probe[0] < 0) probe[0] = w / 2, probe[1] = h / 2;
    probe[0] = std::min(probe[0], w - 1), probe[1] = std::min(probe[1], h - 1);
    ImGui::SliderInt("cone samples: pixel x", &probe[0], 0, w - 1);
    ImGui::SliderInt("cone samples: pixel y", &probe[1], 0, h - 1);
    r->setVctProbePixel(uint32_t(probe[0]), uint32_t(probe[1]));
}

}  // namespace

BRICKLIGHT_VIEWER_TECHNIQUE(Technique{"Voxel cone tracing", "VXGI-class clip-map voxel GI and voxel AO (docs/vct.md).", 20, vctPanel});

}  // namespace bricklight::viewer
