// Heat map tab: the view switch and the colour legend; the value under the cursor shows as a
// tooltip over the image.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "panels.h"

namespace edacrt::app {

void draw_heatmap_tab(ViewerState& s, float heat_max) {
    ImGui::TextDisabled("per pixel, the batch's rays summed (the Statistics tab's batch)");
    for (const EnumEntry<View>& view : kViews) {
        if (ImGui::RadioButton(std::string(view.help).c_str(), s.view == view.value))
            s.view = view.value;
        ImGui::SameLine();
    }
    ImGui::Checkbox("logarithmic", &s.heat_log);
    // With a recording compared with another recursion: A, B or their difference.
    const Analysis* a = s.analysis.get();
    const bool against = a && a->against_detail && !s.analysis_stale;
    if (against) {
        ImGui::TextDisabled("the recording against %s:", a->against.c_str());
        for (const EnumEntry<HeatOf>& of : kHeatOf) {
            ImGui::SameLine();
            if (ImGui::RadioButton(std::string(of.help).c_str(), s.heat_of == of.value))
                s.heat_of = of.value;
        }
    }
    if (s.view != View::render) {
        // The legend: the ramp with its scale (B - A: signed, from -max to +max).
        const bool difference = against && s.heat_of == HeatOf::difference;
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        const float width = std::min(ImGui::GetContentRegionAvail().x, 480.0f), height = 16.0f;
        ImDrawList* draw = ImGui::GetWindowDrawList();
        constexpr int kSteps = 64;
        for (int i = 0; i < kSteps; ++i) {
            const float t = (float(i) + 0.5f) / kSteps;
            const glm::vec3 c = difference ? diverging(2.0f * t - 1.0f) : turbo(t);
            draw->AddRectFilled(ImVec2(origin.x + width * i / kSteps, origin.y),
                                ImVec2(origin.x + width * (i + 1) / kSteps, origin.y + height),
                                ImGui::GetColorU32(ImVec4(c.x, c.y, c.z, 1.0f)));
        }
        ImGui::Dummy(ImVec2(width, height));
        if (difference) {
            ImGui::Text("-%.0f (B fewer)", heat_max);
            ImGui::SameLine(width * 0.48f);
            ImGui::Text("0");
            ImGui::SameLine(width * 0.75f);
            ImGui::Text("+%.0f (B more)", heat_max);
        } else {
            const float mid =
                s.heat_log ? std::expm1(0.5f * std::log1p(heat_max)) : 0.5f * heat_max;
            ImGui::Text("0");
            ImGui::SameLine(width * 0.45f);
            ImGui::Text("%.0f", mid);
            ImGui::SameLine(width * 0.85f);
            ImGui::Text("%.0f", heat_max);
        }

        ImGui::TextDisabled("hover the image for a pixel's values");
    }
}

void draw_heat_readout(const ViewerState& s) {
    const ImGuiIO& io = ImGui::GetIO();
    const Rect& r = s.layout.image;
    const ShownBatch batch = shown_batch(s);
    if (s.view == View::render || io.WantCaptureMouse || !batch.detail || r.empty()) return;
    const int w = batch.width, h = batch.height;
    const int x = int(std::floor((io.MousePos.x - r.x) / r.w * float(w)));
    const int y = int(std::floor((io.MousePos.y - r.y) / r.h * float(h)));
    if (x < 0 || y < 0 || x >= w || y >= h ||
        std::size_t(y) * std::size_t(w) + std::size_t(x) >= batch.pixels.size())
        return;
    const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
    const RayStats& ray = batch.pixels[i];
    // With a recording against another recursion (of the same image), B's counts too.
    const Analysis* a = s.analysis.get();
    std::string other;
    if (a && a->against_detail && !s.analysis_stale && a->width == w && a->height == h &&
        i < a->against_pixel_stats.size()) {
        const RayStats& b = a->against_pixel_stats[i];
        other = "\nB (" + a->against + "): " + std::to_string(b.ray_box_tests) + " box tests, " +
                std::to_string(b.ray_triangle_tests) + " triangle tests";
    }
    ImGui::SetTooltip(
        "pixel (%d, %d)\n%u box tests, %u triangle tests\ndepth %u, %u order misses%s", x, y,
        ray.ray_box_tests, ray.ray_triangle_tests, unsigned(ray.deepest_level),
        unsigned(ray.order_misses), other.c_str());
}

}  // namespace edacrt::app
