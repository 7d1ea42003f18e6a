// Heat maps: the view switch, the colour legend, and the value under the cursor.
#include <imgui.h>

#include <cmath>

#include "viewer_state.h"

namespace edacrt::app {

void draw_heatmap_panel(ViewerState& s, float heat_max) {
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 300, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(290, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("Heat maps", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    for (View view : kViews) {
        if (ImGui::RadioButton(std::string(view_name(view)).c_str(), s.view == view)) s.view = view;
    }
    ImGui::Checkbox("logarithmic", &s.heat_log);
    if (s.view != View::render) {
        // The legend: the turbo ramp with its scale.
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        const float width = ImGui::GetContentRegionAvail().x, height = 16.0f;
        ImDrawList* draw = ImGui::GetWindowDrawList();
        constexpr int kSteps = 64;
        for (int i = 0; i < kSteps; ++i) {
            const glm::vec3 c = turbo((float(i) + 0.5f) / kSteps);
            draw->AddRectFilled(ImVec2(origin.x + width * i / kSteps, origin.y),
                                ImVec2(origin.x + width * (i + 1) / kSteps, origin.y + height),
                                ImGui::GetColorU32(ImVec4(c.x, c.y, c.z, 1.0f)));
        }
        ImGui::Dummy(ImVec2(width, height));
        const float mid = s.heat_log ? std::expm1(0.5f * std::log1p(heat_max)) : 0.5f * heat_max;
        ImGui::Text("0");
        ImGui::SameLine(width * 0.45f);
        ImGui::Text("%.0f", mid);
        ImGui::SameLine(width * 0.85f);
        ImGui::Text("%.0f", heat_max);

        // The value under the cursor, when it is over the image.
        const ImGuiIO& io = ImGui::GetIO();
        if (!io.WantCaptureMouse && s.frame && s.frame->detail) {
            const int w = s.frame->image.width, h = s.frame->image.height;
            const int x = int(io.MousePos.x / io.DisplaySize.x * float(w));
            const int y = int(io.MousePos.y / io.DisplaySize.y * float(h));
            if (x >= 0 && y >= 0 && x < w && y < h &&
                std::size_t(y) * std::size_t(w) + std::size_t(x) < s.frame->detail->rays.size()) {
                const RayStats& r = s.frame->detail->rays[std::size_t(y) * std::size_t(w) + x];
                ImGui::Text("pixel (%d, %d): %u box, %u tri tests, depth %u, %u order misses", x, y,
                            r.ray_box_tests, r.ray_triangle_tests, unsigned(r.deepest_level),
                            unsigned(r.order_misses));
            }
        }
    }
    ImGui::End();
}

}  // namespace edacrt::app
