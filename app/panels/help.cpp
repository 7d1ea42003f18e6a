// The help overlay (H or ?): mouse and keys.
#include <imgui.h>

#include "panels.h"

namespace edacrt::app {

void draw_help(ViewerState& s) {
    if (!s.show_help) return;
    const Rect& r = s.layout.image;
    ImGui::SetNextWindowPos(ImVec2(r.x + r.w * 0.5f, r.y + r.h * 0.5f), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.92f);
    ImGui::Begin("Help", &s.show_help,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoCollapse);
    constexpr const char* kKeys[][2] = {
        {"left drag", "orbit around the look-at point (eye inside the scene's box: look)"},
        {"right drag", "look around, the eye staying where it is"},
        {"middle or Shift + left drag", "pan"},
        {"wheel", "move closer / away"},
        {"double click", "orbit about the point under the cursor"},
        {"W A S D, Q E", "fly forward, left, back, right, down, up"},
        {"+ / -", "fly faster / slower (the Camera tab shows the speed)"},
        {"Ctrl + / Ctrl -, Ctrl 0", "larger / smaller panel text, its default"},
        {"drag the Analysis title", "more or less room for the analysis"},
        {"R", "reset the view to the scene's"},
        {"Tab or F1", "hide / show all panels"},
        {"H or ?", "this help"},
        {"F12", "save the image as shown (Render tab: folder)"},
        {"Esc", "quit"},
        {"Space", "play / pause an animation (the timeline under the image)"},
        {"Left / Right", "an animation 1/24 s back / on"},
        {"click (picking)", "follow a pixel's ray (Traversal tab)"},
        {"drag (drag a region)", "the region to record and step through (Recursion tab)"},
    };
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg)) {
        for (const auto& [key, what] : kKeys) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            cell_text("%s", key);
            ImGui::TableNextColumn();
            cell_text("%s", what);
        }
        ImGui::EndTable();
    }
    ImGui::TextDisabled("Keys act while no text field has the keyboard.");
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    s.items.push_back({"Help", {pos.x, pos.y, size.x, size.y}});
    ImGui::End();
}

}  // namespace edacrt::app
