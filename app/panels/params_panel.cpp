// EDACRT parameters: every field of EdacrtParams; any change re-renders (the viewer compares
// the settings each frame).
#include <imgui.h>

#include <algorithm>

#include "viewer_state.h"

namespace edacrt::app {
namespace {

bool input_u32(const char* label, std::uint32_t& value, int low, int high) {
    int v = int(std::min<std::uint32_t>(value, std::uint32_t(high)));
    if (!ImGui::InputInt(label, &v)) return false;
    value = std::uint32_t(std::clamp(v, low, high));
    return true;
}

}  // namespace

void draw_params_panel(ViewerState& s) {
    ImGui::SetNextWindowPos(ImVec2(10, 430), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("EDACRT parameters");
    EdacrtParams& p = s.ui.params;
    if (s.ui.method != Method::edacrt && s.ui.method != Method::dacrt)
        ImGui::TextDisabled("(used by edacrt and dacrt only)");
    ImGui::SliderInt("bins K", &p.bins, 2, 64);
    input_u32("sample count", p.sample_count, 1, 100000);
    input_u32("sample threshold", p.sample_threshold, 1, 100000000);
    input_u32("leaf rays", p.leaf_rays, 1, 1000000);
    input_u32("leaf triangles", p.leaf_tris, 1, 1000000);
    input_u32("cost-leaf max tris", p.cost_leaf_max_tris, 1, 100000000);
    ImGui::SliderFloat("C_T", &p.cost_traversal, 0.0f, 16.0f);
    ImGui::SliderFloat("C_I", &p.cost_intersect, 0.01f, 16.0f);
    ImGui::SliderFloat("C_bv", &p.cost_filter, 0.0f, 16.0f);
    ImGui::SliderFloat("C_child", &p.cost_child, 0.01f, 16.0f);
    ImGui::Checkbox("filter skipping", &p.filter_skip);
    ImGui::SameLine();
    ImGui::Checkbox("ray sampling", &p.sampling);
    input_u32("sampling seed", p.seed, 0, 1 << 30);
    if (ImGui::Button("defaults")) p = EdacrtParams{};
    ImGui::End();
}

}  // namespace edacrt::app
