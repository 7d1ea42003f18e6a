// Over the image region: the loading notice, and projected wireframes of recursion boxes
// (clipped to it).
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "panels.h"

namespace edacrt::app {

void draw_region(ViewerState& s) {
    const Rect& r = s.layout.image;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const ImGuiIO& io = ImGui::GetIO();
    const ImVec2 a = io.MouseClickedPos[ImGuiMouseButton_Left], b = io.MousePos;
    const bool in_image = a.x >= r.x && a.y >= r.y && a.x < r.right() && a.y < r.bottom();
    if (s.region_picking && ImGui::IsMouseDown(ImGuiMouseButton_Left) && in_image &&
        !io.WantCaptureMouse) {
        draw->PushClipRect(ImVec2(r.x, r.y), ImVec2(r.right(), r.bottom()), true);
        draw->AddRect(ImVec2(std::min(a.x, b.x), std::min(a.y, b.y)),
                      ImVec2(std::max(a.x, b.x), std::max(a.y, b.y)), IM_COL32(80, 220, 255, 255),
                      0.0f, 0, 2.0f);
        draw->PopClipRect();
    }
    const Analysis* an = s.analysis.get();
    if (!s.recursion_shown || !an || !an->cropped() || s.analysis_stale) return;
    const ImVec2 lo = image_to_window(s, float(an->crop_x), float(an->crop_y), an->width,
                                      an->height),
                 hi = image_to_window(s, float(an->crop_x + an->crop_w),
                                      float(an->crop_y + an->crop_h), an->width, an->height);
    draw->AddRect(lo, hi, IM_COL32(80, 220, 255, 200), 0.0f, 0, 1.0f);
}

void draw_loading(ViewerState& s) {
    if (!s.loading) return;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - s.loading->started)
            .count();
    const std::string name = std::filesystem::path(s.loading->spec).filename().string();
    const std::string text = "loading " + (name.empty() ? s.loading->spec : name) + "... " +
                             std::to_string(int(seconds * 10.0) / 10) + "." +
                             std::to_string(int(seconds * 10.0) % 10) + " s";
    const Rect& r = s.layout.image;
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    const float pad = ImGui::GetStyle().WindowPadding.x;
    const ImVec2 at(r.x + 0.5f * (r.w - size.x), r.y + 0.5f * (r.h - size.y));
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    draw->AddRectFilled(ImVec2(at.x - pad, at.y - pad),
                        ImVec2(at.x + size.x + pad, at.y + size.y + pad), IM_COL32(0, 0, 0, 200),
                        pad);
    draw->AddText(at, IM_COL32(255, 255, 255, 255), text.c_str());
    s.items.push_back(
        {"Image/loading", {at.x - pad, at.y - pad, size.x + 2 * pad, size.y + 2 * pad}});
}

ImVec2 image_to_window(const ViewerState& s, float x, float y, int width, int height) {
    const Rect& r = s.layout.image;
    return ImVec2(r.x + x * r.w / float(width), r.y + y * r.h / float(height));
}

void draw_box_overlay(const ViewerState& s, const Analysis& analysis, const Aabb& box,
                      unsigned colour, float thickness) {
    if (box.empty() || s.analysis_stale) return;  // a stale recording would draw wrong boxes
    const PinholeProjection projection(analysis.camera, analysis.width, analysis.height);
    std::optional<glm::vec2> corner[8];
    for (int i = 0; i < 8; ++i)
        corner[i] = projection.pixel({i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                                      i & 4 ? box.hi.z : box.lo.z});
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const Rect& r = s.layout.image;
    draw->PushClipRect(ImVec2(r.x, r.y), ImVec2(r.right(), r.bottom()), true);
    const auto at = [&](const glm::vec2& p) {
        return image_to_window(s, p.x, p.y, analysis.width, analysis.height);
    };
    for (int i = 0; i < 8; ++i)
        for (int bit : {1, 2, 4}) {
            const int j = i | bit;
            if (j == i || !corner[i] || !corner[j]) continue;  // edges behind the eye are left out
            draw->AddLine(at(*corner[i]), at(*corner[j]), colour, thickness);
        }
    draw->PopClipRect();
}

}  // namespace edacrt::app
