// Projected wireframes of recursion boxes over the image region, clipped to it.
#include <imgui.h>

#include "panels.h"

namespace edacrt::app {

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
