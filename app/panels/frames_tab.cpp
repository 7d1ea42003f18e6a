// Frames tab (animated scenes): the live chart of each rendered frame's time with the method
// rendering it, split into the tracer's update (rebuild, refit or nothing) and the first pass,
// and every method measured on the frame shown, on request.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "panels.h"

namespace edacrt::app {
namespace {

ImU32 method_colour(Method method) {
    switch (method) {
        case Method::edacrt:
            return IM_COL32(90, 200, 255, 255);
        case Method::dacrt:
            return IM_COL32(120, 230, 120, 255);
        case Method::bvh:
            return IM_COL32(255, 180, 70, 255);
        case Method::embree:
            return IM_COL32(240, 100, 200, 255);
        case Method::naive:
            return IM_COL32(200, 200, 200, 255);
    }
    return IM_COL32_WHITE;
}

/// update + pass per frame (coloured by method), the update alone dimmer beneath; lines join
/// consecutive frames of one method and resolution.
void chart(const std::vector<Playback::FrameTime>& history, float width, float height) {
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    ImGui::InvisibleButton("##frame_chart", ImVec2(width, height));
    draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height),
                        ImGui::GetColorU32(ImGuiCol_FrameBg));
    if (history.empty()) return;
    double top = 1e-6;
    for (const auto& f : history) top = std::max(top, f.update_seconds + f.pass_seconds);
    top *= 1.1;
    const std::size_t n = history.size();
    const auto at = [&](std::size_t i, double seconds) {
        const float x = n == 1 ? width : float(i) / float(n - 1) * width;
        return ImVec2(origin.x + x, origin.y + height - float(seconds / top) * height);
    };
    for (std::size_t i = 0; i < n; ++i) {
        const auto& b = history[i];
        draw->AddCircleFilled(at(i, b.update_seconds + b.pass_seconds), 2.0f,
                              method_colour(b.method));
        if (i == 0) continue;
        const auto& a = history[i - 1];
        if (a.method != b.method || a.width != b.width || a.height != b.height) continue;
        draw->AddLine(at(i - 1, a.update_seconds), at(i, b.update_seconds),
                      IM_COL32(170, 170, 170, 160), 1.0f);
        draw->AddLine(at(i - 1, a.update_seconds + a.pass_seconds),
                      at(i, b.update_seconds + b.pass_seconds), method_colour(b.method), 2.0f);
    }
    char label[32];
    std::snprintf(label, sizeof label, "%.1f ms", top * 1e3);
    draw->AddText(ImVec2(origin.x + 4, origin.y + 2), ImGui::GetColorU32(ImGuiCol_TextDisabled),
                  label);
    if (ImGui::IsItemHovered()) {
        const float x = ImGui::GetIO().MousePos.x - origin.x;
        const std::size_t i =
            std::min(n - 1, std::size_t(std::max(0.0f, x / width * float(n - 1) + 0.5f)));
        const auto& f = history[i];
        ImGui::SetTooltip("t = %.3f s, %s at %dx%d: update (%s) %.2f ms + first pass %.2f ms",
                          f.time, std::string(enum_name(kMethods, f.method)).c_str(), f.width,
                          f.height, std::string(enum_name(kUpdateWorks, f.work)).c_str(),
                          f.update_seconds * 1e3, f.pass_seconds * 1e3);
    }
}

}  // namespace

void draw_frames_tab(ViewerState& s) {
    const Playback& p = s.playback;
    if (!p.frames) {
        ImGui::TextDisabled(
            "a still scene: choose an animation in the Scene tab, or load an animation file "
            "(assets/animations)");
        return;
    }
    ImGui::TextWrapped(
        "%zu frames rendered; per frame: the tracer's update of the geometry + "
        "the first pass (1 spp); played frames render at 1/%d resolution",
        p.history.size(), p.play_scale);
    if (!p.history.empty()) {
        const auto& last = p.history.back();
        std::size_t count = 0;
        double sum = 0.0;
        for (auto it = p.history.rbegin(); it != p.history.rend() && count < 60; ++it)
            if (it->method == last.method && it->width == last.width) {
                sum += it->update_seconds + it->pass_seconds;
                ++count;
            }
        ImGui::TextWrapped(
            "last: t = %.3f s, %s at %dx%d, update %s %.2f ms + pass %.2f ms; mean "
            "of the last %zu like it: %.2f ms",
            last.time, std::string(enum_name(kMethods, last.method)).c_str(), last.width,
            last.height, std::string(enum_name(kUpdateWorks, last.work)).c_str(),
            last.update_seconds * 1e3, last.pass_seconds * 1e3, count, sum / double(count) * 1e3);
    }
    // The legend: the methods in the chart.
    for (const EnumEntry<Method>& m : kMethods)
        if (std::any_of(p.history.begin(), p.history.end(),
                        [&](const auto& f) { return f.method == m.value; })) {
            ImGui::PushStyleColor(ImGuiCol_Text,
                                  ImGui::ColorConvertU32ToFloat4(method_colour(m.value)));
            ImGui::TextUnformatted(std::string(m.name).c_str());
            ImGui::PopStyleColor();
            ImGui::SameLine();
        }
    ImGui::TextDisabled("(grey: the update alone)");
    chart(p.history, ImGui::GetContentRegionAvail().x, 90.0f);
    draw_comparison(s);
}

}  // namespace edacrt::app
