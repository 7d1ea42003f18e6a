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
namespace {

void tooltip(const char* text) {
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

}  // namespace

void draw_render_tab(ViewerState& s) {
    UiSettings& ui = s.ui;
    ImGui::PushItemWidth(-ImGui::CalcTextSize("resolution").x - ImGui::GetStyle().ItemSpacing.x);
    enum_combo("method", ui.method, kMethods);
    wrapped_tooltip("how rays are traced: " + enum_help(kMethods));
    if (ui.method == Method::embree) enum_combo("embree mode", ui.embree_mode, kEmbreeModes);
    enum_combo("integrator", ui.integrator, kIntegrators);
    wrapped_tooltip("integrator: " + enum_help(kIntegrators));
    if (ui.integrator == Integrator::primary) enum_combo("shading", ui.primary, kPrimaryShadings);
    if (ui.integrator == Integrator::path) ImGui::SliderInt("max depth", &ui.max_depth, 0, 32);
    tooltip("path: bounces after the camera ray");
    if (ui.integrator == Integrator::ao) ImGui::SliderInt("ao rays", &ui.ao_samples, 1, 64);
    ImGui::SliderInt("spp", &ui.spp_target, int(setting_range("spp").min),
                     int(setting_range("spp").ui_max), "%d",
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("samples per pixel to accumulate");
    ImGui::SliderFloat("resolution", &ui.resolution_scale, float(setting_range("resolution").min),
                       float(setting_range("resolution").ui_max), "%.3f x image",
                       ImGuiSliderFlags_AlwaysClamp);
    report_item(s, "Render/resolution");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("render size as a fraction of the image region's pixels");
    if (!s.resolution_error.empty()) {
        error_text(s, "Render/resolution error", s.resolution_error);
    }
    ImGui::SliderInt("threads", &ui.threads, int(setting_range("threads").min),
                     int(setting_range("threads").ui_max), ui.threads == 0 ? "all" : "%d",
                     ImGuiSliderFlags_AlwaysClamp);
    tooltip("worker threads of the renderer and the tracer (0: all cores)");
    if (ImGui::InputInt("seed", &ui.seed))
        ui.seed =
            std::clamp(ui.seed, int(setting_range("seed").min), int(setting_range("seed").max));
    tooltip(
        "the sample sequence: the same seed gives the same image for every method and thread "
        "count");
    ImGui::Checkbox("pause", &ui.paused);

    ImGui::Separator();
    ImGui::SliderFloat("exposure", &s.exposure, -8.0f, 8.0f, "%.1f stops");
    tooltip("display only: radiance times 2^stops before tone mapping");
    enum_combo("tone map", s.tone_map, kToneMaps);
    tooltip("display only: how radiance above 1 is compressed");
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
