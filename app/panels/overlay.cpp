// Projected wireframes of recursion boxes over the image.
#include <imgui.h>

#include "viewer_state.h"

namespace edacrt::app {

void draw_box_overlay(const Analysis& analysis, const Aabb& box, unsigned colour, float thickness) {
    if (box.empty()) return;
    const PinholeProjection projection(analysis.camera, analysis.width, analysis.height);
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float sx = display.x / float(analysis.width), sy = display.y / float(analysis.height);
    std::optional<glm::vec2> corner[8];
    for (int i = 0; i < 8; ++i)
        corner[i] = projection.pixel({i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                                      i & 4 ? box.hi.z : box.lo.z});
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    for (int i = 0; i < 8; ++i)
        for (int bit : {1, 2, 4}) {
            const int j = i | bit;
            if (j == i || !corner[i] || !corner[j]) continue;  // edges behind the eye are left out
            draw->AddLine(ImVec2(corner[i]->x * sx, corner[i]->y * sy),
                          ImVec2(corner[j]->x * sx, corner[j]->y * sy), colour, thickness);
        }
}

}  // namespace edacrt::app
