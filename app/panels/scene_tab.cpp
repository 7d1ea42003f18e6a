// Scene tab: the scene list, a path to load, what is loaded.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <filesystem>

#include "panels.h"

namespace edacrt::app {

void draw_scene_tab(ViewerState& s) {
    ImGui::TextWrapped("%s", s.scene_label.c_str());
    report_item(s, "Scene/label");
    if (s.scene && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", s.scene->source.c_str());
    ImGui::SetNextItemWidth(-1.0f);
    const bool list = ImGui::BeginCombo("##scenes", "choose a scene...");
    report_item(s, "Scene/scenes");
    if (list) {
        for (const CatalogEntry& entry : s.scene_list.entries) {
            ImGui::BeginDisabled(!entry.present);
            if (ImGui::Selectable(entry.label.c_str())) s.pending_loads.push_back(entry.path);
            ImGui::EndDisabled();
        }
        ImGui::EndCombo();
    }
    if (!s.scene_list.hint.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        ImGui::TextWrapped("%s", s.scene_list.hint.c_str());
        ImGui::PopStyleColor();
        report_item(s, "Scene/hint");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("fetched into %s", s.scene_list.scenes_folder.c_str());
    }
    ImGui::SetNextItemWidth(-ImGui::CalcTextSize("Load").x -
                            2.0f * ImGui::GetStyle().FramePadding.x -
                            ImGui::GetStyle().ItemSpacing.x);
    ImGui::InputText("##path", &s.scene_path);
    report_item(s, "Scene/path");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "an OBJ file, or builtin:cornell, builtin:sphere:subdiv=N, "
            "builtin:cube:n=N; or drop a file on the window");
    ImGui::SameLine();
    if (ImGui::Button("Load")) s.pending_loads.push_back(s.scene_path);
    report_item(s, "Scene/load");
    if (s.loading) {
        const std::string name = std::filesystem::path(s.loading->spec).filename().string();
        ImGui::TextDisabled("loading %s...", (name.empty() ? s.loading->spec : name).c_str());
        report_item(s, "Scene/loading");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", s.loading->spec.c_str());
    }
    if (!s.scene_error.empty()) error_text(s, "Scene/error", s.scene_error);
    draw_animation_settings(s);
    if (s.scene) {
        ImGui::Separator();
        const Aabb box = s.scene->bounds();
        ImGui::Text("%zu triangles, %zu vertices", s.scene->triangle_count(),
                    s.scene->positions.size());
        ImGui::Text("%zu materials", s.scene->materials.size());
        ImGui::TextWrapped("bounds (%.4g, %.4g, %.4g) to (%.4g, %.4g, %.4g)", box.lo.x, box.lo.y,
                           box.lo.z, box.hi.x, box.hi.y, box.hi.z);
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        for (const std::string& w : s.scene->warnings) ImGui::TextWrapped("%s", w.c_str());
        ImGui::PopStyleColor();
    }
}

}  // namespace edacrt::app
