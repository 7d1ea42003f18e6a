// Camera tab: the view's numbers (editable), the field of view, the `edacrt render` command
// that reproduces the view, and bookmarks saved per scene.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <glm/gtc/type_ptr.hpp>
#include <iostream>

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
    ImGui::PushItemWidth(-ImGui::CalcTextSize("look-at").x - ImGui::GetStyle().ItemSpacing.x);
    edited |= ImGui::InputFloat3("eye", glm::value_ptr(c.eye), "%.4g",
                                 ImGuiInputTextFlags_EnterReturnsTrue);
    edited |= ImGui::InputFloat3("look-at", glm::value_ptr(c.look_at), "%.4g",
                                 ImGuiInputTextFlags_EnterReturnsTrue);
    edited |= ImGui::InputFloat3("up", glm::value_ptr(c.up), "%.4g",
                                 ImGuiInputTextFlags_EnterReturnsTrue);
    edited |= ImGui::SliderFloat("fov", &c.vfov_degrees, 5.0f, 150.0f, "%.1f deg");
    ImGui::PopItemWidth();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("vertical field of view, degrees");
    if (edited) {
        try {
            validate(c);
            s.camera.reset(c);
        } catch (const std::exception& e) {
            s.status = e.what();
        }
    }
    if (ImGui::Button("reset view (R)")) s.camera.reset(s.scene_camera);

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
        if (ImGui::SmallButton("go")) s.camera.reset(b.camera);
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
