// Render tab: method, integrator, samples, resolution, threads, seed, pause, tone mapping,
// saving, progress.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <vector>

#include "panels.h"
#include "render/image_format.h"

namespace edacrt::app {

void draw_render_tab(ViewerState& s) {
    const UiSettings& ui = s.ui;
    ImGui::PushItemWidth(-ImGui::CalcTextSize("resolution").x - ImGui::GetStyle().ItemSpacing.x);
    setting_widget(s, "method");
    if (ui.method == Method::embree) setting_widget(s, "embree-mode");
    setting_widget(s, "integrator");
    if (ui.integrator == Integrator::primary) setting_widget(s, "primary");
    if (ui.integrator == Integrator::path) setting_widget(s, "max-depth");
    if (ui.integrator == Integrator::ao) setting_widget(s, "ao-samples");
    setting_widget(s, "spp");
    setting_widget(s, "resolution", {nullptr, "%.3f x image", "Render/resolution"});
    if (!s.resolution_error.empty()) {
        error_text(s, "Render/resolution error", s.resolution_error);
    }
    setting_widget(s, "threads", {nullptr, ui.threads == 0 ? "all" : "%d"});
    setting_widget(s, "seed");
    setting_widget(s, "pause");

    ImGui::Separator();
    setting_widget(s, "exposure", {nullptr, "%.1f stops"});
    setting_widget(s, "tone-map");
    setting_widget(s, "font-scale", {nullptr, "%.2fx"});
    ImGui::PopItemWidth();

    ImGui::Separator();
    if (ImGui::Button("save PNG (F12)")) s.save_requested = ViewerState::Save::shown;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the image region as shown: the render or heat map, tone-mapped");
    ImGui::SameLine();
    ImGui::Checkbox("overlays", &s.save_overlays);
    ImGui::SameLine();
    if (ImGui::Button("save EXR")) s.save_requested = ViewerState::Save::linear;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "the render's linear radiance as float OpenEXR, with the method, spp and camera in "
            "its header (the script's save-linear FILE takes %s)",
            enum_names(kImageFormats).c_str());
    ImGui::SetNextItemWidth(-ImGui::CalcTextSize("folder").x - ImGui::GetStyle().ItemSpacing.x);
    ImGui::InputText("folder", &s.save_dir);
    if (!s.status.empty()) ImGui::TextWrapped("%s", s.status.c_str());

    ImGui::Separator();
    if (!s.render_error.empty()) {
        error_text(s, "Render/render error", s.render_error);
    } else if (s.frame) {
        const Frame& f = *s.frame;
        const double mrays = f.total.trace_seconds > 0
                                 ? double(f.total.trace.rays) / f.total.trace_seconds * 1e-6
                                 : 0.0;
        ImGui::Text("%dx%d  %s%d spp  %.2f s", f.image.width, f.image.height,
                    f.preview ? "preview, " : "", f.spp, f.seconds);
        ImGui::Text("%.2f Mrays/s in the tracer (%.0f%%)", mrays,
                    f.seconds > 0 ? 100.0 * f.total.trace_seconds / f.seconds : 0.0);
        ImGui::ProgressBar(float(f.spp) / float(std::max(ui.spp_target, 1)));
        if (s.convergence.size() >= 2) {
            // log10 of the change per pass: a straight line of slope -1/2 per decade of
            // samples is Monte Carlo's 1/sqrt(N).
            std::vector<float> values;
            for (const auto& p : s.convergence)
                values.push_back(float(std::log10(std::max(p.change, 1e-12))));
            const auto& last = s.convergence.back();
            char overlay[96];
            std::snprintf(overlay, sizeof overlay, "%.2e at %d spp, %.1f s", last.change, last.spp,
                          last.seconds);
            ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
            ImGui::TextWrapped("convergence: log10 of each pass's relative RMS change");
            ImGui::PopStyleColor();
            ImGui::PlotLines("##convergence", values.data(), int(values.size()), 0, overlay,
                             FLT_MAX, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 70.0f));
        }
        if (s.comparing) ImGui::TextDisabled("paused while methods are compared");
    }
}

}  // namespace edacrt::app
