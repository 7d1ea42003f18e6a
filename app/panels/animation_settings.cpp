// The Scene tab's animation section: a deformation of the loaded scene (or the animation file
// that is loaded), how the BVH and Embree take each new frame, and motion blur.
#include <imgui.h>
#include <imgui_stdlib.h>

#include "panels.h"
#include "viewer_jobs.h"

namespace edacrt::app {

void draw_animation_settings(ViewerState& s) {
    Playback& p = s.playback;
    ImGui::Separator();
    ImGui::TextUnformatted("Animation");
    const bool own = p.frames && s.animation_spec.empty();  // a file or sequence
    if (own) {
        ImGui::TextWrapped("%s", p.frames->spec().c_str());
    } else {
        // The deformations of any scene, with their default parameters; the field takes
        // any spec (parameters spelled out).
        for (const char* kind : {"none", "wave", "twist", "explode"}) {
            const std::string spec = std::string(kind) == "none" ? "" : kind;
            const bool current = s.animation_spec.substr(0, s.animation_spec.find(':')) == spec;
            if (ImGui::RadioButton(kind, current) && !current)
                load_into(s, s.scene_path, {}, spec, true);
            ImGui::SameLine();
        }
        ImGui::NewLine();
        ImGui::SetNextItemWidth(-ImGui::CalcTextSize("Apply").x -
                                2.0f * ImGui::GetStyle().FramePadding.x -
                                ImGui::GetStyle().ItemSpacing.x);
        ImGui::InputText("##animation", &s.animation_field);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", animation_help().c_str());
        ImGui::SameLine();
        if (ImGui::Button("Apply")) load_into(s, s.scene_path, {}, s.animation_field, true);
    }
    if (!p.frames) return;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8.0f);
    setting_widget(s, "update");
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 12.0f);
    setting_widget(s, "play-scale");
    ImGui::Checkbox("motion blur", &p.motion_blur);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "passes are rendered at times spread over the shutter around the frame's time\n"
            "and averaged: the blur converges while the animation is paused (each played\n"
            "frame shows its first pass, at the frame's time)");
    if (p.motion_blur) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);
        setting_widget(s, "shutter", {nullptr, "%.3f"});
    }
    if (!p.error.empty()) error_text(s, "Scene/animation error", p.error);
}

}  // namespace edacrt::app
