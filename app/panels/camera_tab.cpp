// Camera tab: the view's numbers (editable), the field of view, the `edacrt render` command
// that reproduces the view, and bookmarks saved per scene.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

#include "panels.h"
#include "util/printable.h"
#include "viewer_jobs.h"

namespace edacrt::app {
namespace {

/// Runs a bookmark change that writes the file; a failure goes to the status line and stderr.
template <typename F>
void change_bookmarks(ViewerState& s, F&& change) {
    try {
        change();
    } catch (const std::exception& e) {
        s.status = e.what();
        std::cerr << "edacrt_viewer: error: " << printable(s.status) << "\n";
    }
}

}  // namespace

void draw_camera_tab(ViewerState& s) {
    Camera c = s.camera.camera();
    bool edited = false;
    // One widget per camera setting, labelled by its flag (render/camera_options.h).
    float label = 0.0f;
    for (const CameraParam& param : camera_params())
        label = std::max(label, ImGui::CalcTextSize(std::string(param.key).c_str()).x);
    ImGui::PushItemWidth(-label - ImGui::GetStyle().ItemSpacing.x);
    for (const CameraParam& param : camera_params()) {
        const std::string key(param.key), format(param.ui_format);
        if (param.count == 3)
            edited |= ImGui::InputFloat3(key.c_str(), param.field(c), format.c_str(),
                                         ImGuiInputTextFlags_EnterReturnsTrue);
        else
            edited |= ImGui::SliderFloat(key.c_str(), param.field(c), param.ui_min, param.ui_max,
                                         format.c_str());
        wrapped_tooltip(std::string(param.help));
    }
    ImGui::PopItemWidth();
    if (edited) change_camera(s, [&] { s.camera.reset(c); });
    if (ImGui::Button("reset view (R)")) change_camera(s, [&] { s.camera.reset(s.scene_camera); });
    if (s.scene) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.0f);
        char speed[32];  // the slider shows the speed, not the step
        std::snprintf(speed, sizeof speed, "%.3g /s",
                      double(fly_speed(s.scene->bounds(), s.fly_speed_step)));
        ImGui::SliderInt("fly speed", &s.fly_speed_step, -kFlySpeedSteps, kFlySpeedSteps, speed);
        wrapped_tooltip(
            "WASD, QE: world units per second, a tenth of the scene's diagonal at "
            "0, times 1.25 per step (+ / - keys)");
    }

    ImGui::Separator();
    if (ImGui::Button("copy as command line")) ImGui::SetClipboardText(s.command_line.c_str());
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the edacrt render command that renders this view, to the clipboard");
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s", s.command_line.c_str());
    ImGui::PopTextWrapPos();

    ImGui::Separator();
    ImGui::TextUnformatted("bookmarks of this scene");
    ImGui::SetNextItemWidth(-ImGui::CalcTextSize("save view").x -
                            2.0f * ImGui::GetStyle().FramePadding.x -
                            ImGui::GetStyle().ItemSpacing.x);
    ImGui::InputTextWithHint("##bookmark", "name", &s.bookmark_name);
    ImGui::SameLine();
    if (ImGui::Button("save view") && !s.bookmark_name.empty())
        change_bookmarks(s, [&] { save_bookmark(s, s.bookmark_name); });
    std::string remove;
    for (const Bookmark& b : s.bookmarks.of(s.scene_path)) {
        ImGui::PushID(b.name.c_str());
        if (ImGui::SmallButton("go")) change_camera(s, [&] { s.camera.reset(b.camera); });
        ImGui::SameLine();
        if (ImGui::SmallButton("x")) remove = b.name;
        ImGui::SameLine();
        ImGui::TextUnformatted(b.name.c_str());
        ImGui::PopID();
    }
    if (!remove.empty()) change_bookmarks(s, [&] { remove_bookmark(s, remove); });
    if (!s.bookmarks_path.empty()) ImGui::TextDisabled("in %s", s.bookmarks_path.c_str());
}

}  // namespace edacrt::app
