// The timeline under the image of an animated scene: play or pause, step a frame, scrub, speed
// and loop. The time moves only once the shown frame has its first pass (app/playback.cpp).
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "panels.h"

namespace edacrt::app {

void draw_timeline(ViewerState& s) {
    Playback& p = s.playback;
    if (s.layout.timeline.empty() || !p.frames) return;
    const Rect& r = s.layout.timeline;
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(r.w, r.h), ImGuiCond_Always);
    ImGui::Begin("Timeline", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus);
    constexpr double kStep = 1.0 / 24.0;  // one frame at 24 fps
    if (ImGui::Button(p.playing ? "pause" : "play ", ImVec2(ImGui::GetFontSize() * 3.2f, 0)))
        toggle_play(s);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Space: play or pause");
    ImGui::SameLine();
    if (ImGui::ArrowButton("##back", ImGuiDir_Left)) seek(s, p.time - kStep);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("one frame (1/24 s) back (Left)");
    ImGui::SameLine();
    if (ImGui::ArrowButton("##forward", ImGuiDir_Right)) seek(s, p.time + kStep);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("one frame (1/24 s) on (Right)");
    ImGui::SameLine();
    const float speed_width = ImGui::GetFontSize() * 6.5f;
    const float loop_width = ImGui::GetFrameHeight() + ImGui::CalcTextSize("loop").x +
                             ImGui::GetStyle().ItemInnerSpacing.x;
    const float spacing = ImGui::GetStyle().ItemSpacing.x;
    ImGui::SetNextItemWidth(std::max(
        ImGui::GetContentRegionAvail().x - speed_width - loop_width - 2.0f * spacing, 40.0f));
    // Scrubbing pauses: the frame under the slider is the one rendered.
    float time = float(p.time);
    char label[64];
    std::snprintf(label, sizeof label, "%.3f / %.3f s", p.time, p.frames->duration());
    if (ImGui::SliderFloat("##time", &time, 0.0f, float(p.frames->duration()), label)) {
        p.playing = false;
        seek(s, double(time));
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(speed_width);
    setting_widget(s, "speed", {"##speed", "speed %.2gx"});
    ImGui::SameLine();
    setting_widget(s, "loop");
    if (!p.error.empty() && ImGui::IsWindowHovered()) ImGui::SetTooltip("%s", p.error.c_str());
    s.placements.push_back({"Timeline",
                            {ImGui::GetWindowPos().x, ImGui::GetWindowPos().y,
                             ImGui::GetWindowSize().x, ImGui::GetWindowSize().y},
                            take_clipped_cells()});
    ImGui::End();
}

}  // namespace edacrt::app
