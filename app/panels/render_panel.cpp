// Render panel: scene, method, integrator, samples, resolution, threads, seed, pause, save,
// progress.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <cstdio>

#include "render/image_format.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

template <typename Enum, std::size_t N>
bool combo(const char* label, Enum& value, const Enum (&options)[N],
           std::string_view (*name)(Enum)) {
    bool changed = false;
    if (ImGui::BeginCombo(label, std::string(name(value)).c_str())) {
        for (Enum option : options)
            if (ImGui::Selectable(std::string(name(option)).c_str(), option == value)) {
                changed = option != value;
                value = option;
            }
        ImGui::EndCombo();
    }
    return changed;
}

constexpr Method kMethods[] = {Method::edacrt, Method::dacrt, Method::bvh, Method::embree,
                               Method::naive};
constexpr Integrator kIntegrators[] = {Integrator::primary, Integrator::ao, Integrator::path};
constexpr PrimaryShading kShadings[] = {PrimaryShading::eye_light, PrimaryShading::normal,
                                        PrimaryShading::albedo, PrimaryShading::depth};
constexpr EmbreeMode kEmbreeModes[] = {EmbreeMode::single, EmbreeMode::packet8, EmbreeMode::stream};

}  // namespace

void draw_render_panel(ViewerState& s) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, 412), ImGuiCond_FirstUseEver);
    ImGui::Begin("Render");

    ImGui::TextUnformatted(s.scene_label.c_str());
    if (ImGui::BeginCombo("scene", "choose...")) {
        for (const std::string& name : s.scene_list)
            if (ImGui::Selectable(name.c_str())) s.pending_loads.push_back(name);
        ImGui::EndCombo();
    }
    ImGui::InputText("path", &s.scene_path);
    ImGui::SameLine();
    if (ImGui::Button("Load")) s.pending_loads.push_back(s.scene_path);
    if (!s.scene_error.empty())
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", s.scene_error.c_str());
    ImGui::Separator();

    UiSettings& ui = s.ui;
    combo("method", ui.method, kMethods, method_name);
    if (ui.method == Method::embree)
        combo("embree mode", ui.embree_mode, kEmbreeModes, embree_mode_name);
    combo("integrator", ui.integrator, kIntegrators, integrator_name);
    if (ui.integrator == Integrator::primary)
        combo("shading", ui.primary, kShadings, primary_shading_name);
    if (ui.integrator == Integrator::path) ImGui::SliderInt("max depth", &ui.max_depth, 0, 32);
    if (ui.integrator == Integrator::ao) ImGui::SliderInt("ao rays", &ui.ao_samples, 1, 64);
    ImGui::SliderInt("spp target", &ui.spp_target, 1, 65536, "%d", ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("resolution", &ui.resolution_scale, 0.125f, 1.0f, "%.3f x window");
    if (!s.resolution_error.empty())
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", s.resolution_error.c_str());
    ImGui::SliderInt("threads", &ui.threads, 0, 64, ui.threads == 0 ? "all" : "%d");
    ImGui::InputInt("seed", &ui.seed);
    ImGui::Checkbox("pause", &ui.paused);
    ImGui::SameLine();
    if (ImGui::Button("reset view")) s.camera.reset(s.scene_camera);

    ImGui::Separator();
    ImGui::SliderFloat("exposure", &s.exposure, -8.0f, 8.0f, "%.1f stops");
    ImGui::Combo("tone map", &s.tone_map, "clamp\0Reinhard\0ACES\0");
    ImGui::InputText("##save", &s.save_path);
    ImGui::SameLine();
    if (ImGui::Button("save")) s.save_requested = true;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "the extension chooses the format: %s (PNG and JPEG tone-mapped as "
            "shown, the others linear radiance)",
            image_extensions().c_str());
    if (!s.status.empty()) ImGui::TextUnformatted(s.status.c_str());

    ImGui::Separator();
    if (!s.render_error.empty()) {
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", s.render_error.c_str());
    } else if (s.frame) {
        const Frame& f = *s.frame;
        const double mrays = f.total.trace_seconds > 0
                                 ? double(f.total.trace.rays) / f.total.trace_seconds * 1e-6
                                 : 0.0;
        ImGui::Text("%dx%d  %s%d spp  %.2f s", f.image.width, f.image.height,
                    f.preview ? "preview, " : "", f.spp, f.seconds);
        ImGui::Text("%.2f Mrays/s in the tracer, %.0f%% of the time", mrays,
                    f.seconds > 0 ? 100.0 * f.total.trace_seconds / f.seconds : 0.0);
        ImGui::ProgressBar(float(f.spp) / float(std::max(ui.spp_target, 1)));
    }
    ImGui::End();
}

}  // namespace edacrt::app
