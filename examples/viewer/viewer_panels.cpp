// ViewerApp::drawPanels: the Dear ImGui window (docs/viewer.md, "Panels"). Techniques add their own sections
// through technique_registry.h; this file does not know them.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdio>

#include "technique_registry.h"
#include "viewer_app.h"

namespace bricklight::viewer {

namespace {

// A combo over the views; views that need GI are greyed out while it is off.
bool viewCombo(const char* label, render::View* view, bool giOn) {
    bool changed = false;
    if (ImGui::BeginCombo(label, render::viewName(*view))) {
        for (uint32_t v = 0; v < uint32_t(render::View::Count); ++v) {
            const render::View candidate = render::View(v);
            const bool usable = giOn || !render::viewNeedsGi(candidate);
            if (ImGui::Selectable(render::viewName(candidate), candidate == *view, usable ? 0 : ImGuiSelectableFlags_Disabled)) {
                *view = candidate;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

std::string megabytes(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f MiB", double(bytes) / (1024.0 * 1024.0));
    return text;
}

void memoryTable(const char* title, const sdf::MemoryUse& use) {
    ImGui::Text("%s: %s", title, megabytes(use.totalBytes).c_str());
    ImGui::Indent();
    for (const sdf::MemoryUse::Resource& r : use.resources) ImGui::Text("%-28s %s", r.name.c_str(), megabytes(r.bytes).c_str());
    ImGui::Unindent();
}

}  // namespace

void ViewerApp::drawPanels() {
    // --open-panels: every section open (the tests run each panel's code once; docs' screenshots).
    auto header = [&](const char* label, ImGuiTreeNodeFlags flags = 0) {
        if (settings_.openPanels) ImGui::SetNextItemOpen(true, ImGuiCond_Always);
        return ImGui::CollapsingHeader(label, flags);
    };
    // A fixed place, so that tests can click the first widgets (tests/viewer).
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(false, ImGuiCond_FirstUseEver);
    ImGui::Begin("Bricklight", nullptr, ImGuiWindowFlags_NoMove);
    bool gi = settings_.render.gi;
    if (ImGui::Checkbox("GI", &gi)) setGiEnabled(gi);
    ImGui::SameLine();
    ImGui::Text("%s, %ux%u, %.1f ms/frame", backend_->name(), renderWidth_, renderHeight_, stats_.averageCpuMilliseconds());

    if (header("View", ImGuiTreeNodeFlags_DefaultOpen)) {
        render::View view = settings_.view;
        if (viewCombo("view", &view, settings_.render.gi)) setView(view);
        ImGui::SliderFloat("exposure", &settings_.render.exposure, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        bool pip = settings_.pip;
        if (ImGui::Checkbox("picture-in-picture", &pip)) settings_.pip = pip && (settings_.render.gi || !render::viewNeedsGi(settings_.pipView));
        ImGui::SameLine();
        ImGui::SetNextItemWidth(150);
        viewCombo("##pip", &settings_.pipView, settings_.render.gi);
        bool follow = !settings_.fixedSize;
        if (ImGui::Checkbox("render at the window's size", &follow)) {
            settings_.fixedSize = !follow;
            settings_.render.width = renderWidth_;
            settings_.render.height = renderHeight_;
            rebuild_ = true;
        }
        if (ImGui::Checkbox("vsync", &settings_.vsync)) backend_->setVsync(settings_.vsync);
        int limit = int(settings_.fpsLimit);
        if (ImGui::SliderInt("frame limit (0: none)", &limit, 0, 240)) settings_.fpsLimit = uint32_t(limit);
    }

    if (header("Camera")) {
        ImGui::Text("%s, speed %.3g/s (scroll), WASD QE, right mouse to look, Tab: orbit",
                    camera_.mode() == FlyCamera::Mode::Fly ? "fly" : "orbit", camera_.speed());
        for (size_t i = 0; i < bookmarks_.size(); ++i) {
            char label[96];
            std::snprintf(label, sizeof label, "%zu: %s", i + 1, bookmarks_[i].name.c_str());
            if (ImGui::Button(label)) keys_.push_back(GLFW_KEY_1 + int(i));
        }
        if (scene_.animate) {
            if (ImGui::Button(playing_ ? "pause animation" : "play animation")) keys_.push_back(GLFW_KEY_SPACE);
            ImGui::SameLine();
            ImGui::Text("frame %u", animationFrame_);
        }
    }

    if (header("Light")) {
        bool changed = ImGui::SliderFloat("sun azimuth", &lights_.sunAzimuthDegrees, -180.0f, 180.0f, "%.0f deg");
        changed |= ImGui::SliderFloat("sun elevation", &lights_.sunElevationDegrees, -10.0f, 90.0f, "%.0f deg");
        changed |= ImGui::SliderFloat("sun irradiance", &lights_.sunIrradiance, 0.0f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        changed |= ImGui::ColorEdit3("sun colour", &lights_.sunColor.x);
        changed |= ImGui::Checkbox("emitters", &lights_.emitters);
        ImGui::SameLine();
        changed |= ImGui::Checkbox("point lights", &lights_.pointLights);
        if (changed) requestLightUpdate();
    }

    for (const Technique& t : registeredTechniques()) {
        if (!header(t.name.c_str())) continue;
        if (!t.description.empty()) ImGui::TextWrapped("%s", t.description.c_str());
        ImGui::PushID(t.name.c_str());
        t.panel(*this);
        ImGui::PopID();
    }

    if (header("GPU timings")) {
        const std::vector<float>& gpu = stats_.gpuFrameHistory();
        const std::vector<float>& cpu = stats_.cpuFrameHistory();
        if (!cpu.empty()) ImGui::PlotLines("frame (CPU) ms", cpu.data(), int(cpu.size()), 0, nullptr, 0.0f, FLT_MAX, ImVec2(0, 50));
        if (!gpu.empty()) ImGui::PlotLines("GPU ms", gpu.data(), int(gpu.size()), 0, nullptr, 0.0f, FLT_MAX, ImVec2(0, 50));
        if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
            for (const FrameStats::Pass& p : stats_.passes()) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(p.label.c_str());
                ImGui::TableNextColumn();
                ImGui::Text("%.3f ms", p.milliseconds);
            }
            ImGui::EndTable();
        }
    }

    if (header("Memory")) {
        memoryTable("renderer", renderer_->memoryUse());
        if (renderer_->sdfScene()) memoryTable("SDF", renderer_->sdfScene()->memoryUse());
        if (renderer_->giContext()) memoryTable("GI", renderer_->giContext()->memoryUse());
        if (!renderer_->sdfScene()) ImGui::TextUnformatted("GI is off: no SDF or GI resources");
    }

    if (header("Messages")) {
        for (const std::string& m : messages_) ImGui::TextWrapped("%s", m.c_str());
    }
    ImGui::End();
}

}  // namespace bricklight::viewer
