// The SDF GI technique's panel (Brixelizer GI: include/bricklight/sdf.h, gi.h): its tuning, live where the
// library takes it per frame, and the distance field's statistics. Registered, not called by the UI code.
#include <imgui.h>

#include <algorithm>

#include "technique_registry.h"
#include "viewer_app.h"

namespace bricklight::viewer {

namespace {

void sdfGiPanel(ViewerApp& app) {
    GiSettings& g = app.gi();
    render::RenderOptions& options = app.settings().render;
    bool gi = options.gi;
    if (ImGui::Checkbox("enabled", &gi)) app.setGiEnabled(gi);
    if (!options.gi) return;

    // Fixed at creation: these rebuild the renderer (GI starts converging again).
    const char* scales[] = {"100 %", "75 %", "50 %", "25 %"};
    int scale = int(options.giScale);
    if (ImGui::Combo("internal resolution", &scale, scales, 4)) {
        options.giScale = gi::InternalResolution(scale);
        app.requestRebuild();
    }
    const char* injectTiles[] = {"auto", "1", "2", "4", "8"};
    const uint32_t injectValues[] = {0, 1, 2, 4, 8};
    int inject = 0;
    while (inject < 4 && injectValues[inject] != g.injectTile) ++inject;
    if (ImGui::Combo("inject tile", &inject, injectTiles, 5)) {
        g.injectTile = injectValues[inject];
        app.requestRebuild();
    }
    const char* probeTiles[] = {"auto", "8", "16"};
    int probe = g.probeTile == 8 ? 1 : g.probeTile == 16 ? 2 : 0;
    if (ImGui::Combo("probe tile", &probe, probeTiles, 3)) {
        g.probeTile = probe == 1 ? 8 : probe == 2 ? 16 : 0;
        app.requestRebuild();
    }
    if (ImGui::Checkbox("relight off screen", &g.relight)) app.requestRebuild();
    int cascades = int(g.sdfCascades);
    if (ImGui::SliderInt("SDF cascades", &cascades, 1, int(sdf::kMaxCascades))) {
        g.sdfCascades = uint32_t(cascades);
        app.requestRebuild();
    }
    // The field's budgets per update: what does not fit is deferred to later updates (the statistics below).
    int voxels = int(std::min<uint32_t>(g.sdfBudgets.maxVoxelsPerUpdate, 1u << 24));
    if (ImGui::SliderInt("voxels per update", &voxels, 64, 1 << 24, "%d", ImGuiSliderFlags_Logarithmic)) {
        g.sdfBudgets.maxVoxelsPerUpdate = uint32_t(voxels);
        app.requestRebuild();
    }
    int jobs = int(g.sdfBudgets.maxJobsPerUpdate);
    if (ImGui::SliderInt("jobs per update", &jobs, 1, 4096, "%d", ImGuiSliderFlags_Logarithmic)) {
        g.sdfBudgets.maxJobsPerUpdate = uint32_t(jobs);
        app.requestRebuild();
    }
    int triangles = int(std::min<uint32_t>(g.sdfBudgets.maxTrianglesPerUpdate, 1u << 24));
    if (ImGui::SliderInt("triangles per update", &triangles, 1024, 1 << 24, "%d", ImGuiSliderFlags_Logarithmic)) {
        g.sdfBudgets.maxTrianglesPerUpdate = uint32_t(triangles);
        app.requestRebuild();
    }

    // Live: the next frame's gi::DispatchDesc.
    ImGui::Separator();
    ImGui::TextUnformatted("tracing (live)");
    // Within the field's cascades (the library refuses a start past the last or an end before the start).
    const int last = int(g.sdfCascades) - 1;
    int start = std::min(int(g.trace.startCascade), last), end = std::clamp(int(std::min<uint32_t>(g.trace.endCascade, 255)), start, last);
    ImGui::SliderInt("start cascade", &start, 0, last);
    end = std::max(end, start);
    ImGui::SliderInt("end cascade", &end, start, last);
    g.trace.startCascade = uint32_t(start);
    g.trace.endCascade = uint32_t(std::max(end, start));
    int iterations = int(g.trace.maxIterationsPerCascade);
    if (ImGui::SliderInt("steps per cascade", &iterations, 1, 256)) g.trace.maxIterationsPerCascade = uint32_t(iterations);
    ImGui::SliderFloat("coarsen after voxels", &g.trace.coarsenAfterVoxels, 0.0f, 16.0f, "%.1f");
    ImGui::SliderFloat("epsilon scale", &g.trace.epsilonScale, 0.25f, 4.0f, "%.2f");
    ImGui::SliderFloat("ray push-off (0: auto)", &g.trace.rayPushOff, 0.0f, 0.5f, "%.3f", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("specular roughness cut", &g.roughnessThreshold, 0.0f, 1.0f, "%.2f");

    render::RasterRenderer* r = app.renderer();
    if (!r || !r->sdfScene()) return;
    ImGui::Separator();
    ImGui::TextUnformatted("distance field");
    const glm::vec3 c = r->sdfCenter();
    ImGui::Text("centre (%.3g, %.3g, %.3g)", c.x, c.y, c.z);
    const glm::vec3 extent = app.scene().boundsMax - app.scene().boundsMin;
    const float reach = std::max(extent.x, std::max(extent.y, extent.z));
    ImGui::SliderFloat3("centre offset (live)", &g.sdfCenterOffset.x, -reach, reach, "%.3g");
    for (uint32_t k = 0; k < r->sdfScene()->desc().cascadeCount; ++k)
        ImGui::Text("cascade %u: voxel %.3g", k, r->sdfScene()->cascadeVoxelSize(k));
    const sdf::Stats s = r->sdfScene()->latestStats();
    ImGui::Text("bricks %u used, %u free of %u", s.bricksUsed, s.bricksFree, s.bricksCapacity);
    ImGui::Text("last update: %u allocated, %u freed, %u voxels built", s.bricksAllocated, s.bricksFreed, s.voxelsBuilt);
    ImGui::Text("deferred on the GPU: %u voxels; triangles rejected: %u", s.voxelsDeferredGpu, s.trianglesRejected);
    // (Not GiContext::radianceCacheBricksInUse(): a blocking read-back, refused inside an embedded frame.)
}

}  // namespace

BRICKLIGHT_VIEWER_TECHNIQUE(Technique{"SDF GI", "Sparse brick distance field + Brixelizer-class GI (docs/gi.md).", 10, sdfGiPanel});

}  // namespace bricklight::viewer
