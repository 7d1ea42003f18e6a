// Traversal debugger: click a pixel to follow its camera ray through the recursion: the nodes
// it entered, which child went first and whether that was the one holding the final hit,
// where it was filtered out or passed down unfiltered, and the leaf that produced the hit.
#include <imgui.h>

#include <set>

#include "viewer_state.h"

namespace edacrt::app {

void draw_traversal_panel(ViewerState& s) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(720, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(250, 300), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);  // opened when wanted
    if (!ImGui::Begin("Traversal debugger")) {
        ImGui::End();
        return;
    }
    ImGui::Checkbox("pick a pixel (click the image)", &s.picking);
    const Analysis* a = s.analysis.get();
    if (!a || a->pixel < 0 || !a->detail) {
        ImGui::TextDisabled(s.analysis_running ? "tracing..." : "no pixel followed yet");
        ImGui::End();
        return;
    }
    const auto& nodes = a->detail->nodes;
    const auto& visits = a->detail->follow;
    const int x = int(a->pixel % a->width), y = int(a->pixel / a->width);
    ImGui::Text("pixel (%d, %d): %s", x, y,
                a->hit.hit() ? ("triangle " + std::to_string(a->hit.prim) +
                                " at t = " + std::to_string(a->hit.t))
                                   .c_str()
                             : "no hit");
    if (visits.empty()) {
        ImGui::TextDisabled("(%s records no recursion, or the ray missed the scene's box)",
                            std::string(method_name(a->method)).c_str());
        ImGui::End();
        return;
    }
    // The path to the leaf of the final hit: the last leaf where the hit changed, then up.
    std::set<std::int32_t> hit_path;
    for (auto it = visits.rbegin(); it != visits.rend(); ++it)
        if (it->hit_here) {
            for (std::int32_t n = it->node; n >= 0; n = nodes[std::size_t(n)].parent)
                hit_path.insert(n);
            break;
        }
    int order_misses = 0;
    if (ImGui::BeginTable("visits", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollY,
                          ImVec2(0, 220))) {
        for (const char* h : {"depth", "node", "rays/tris", "what happened"})
            ImGui::TableSetupColumn(h);
        ImGui::TableSetupScrollFreeze(0, 1);
        ImGui::TableHeadersRow();
        for (const RayVisit& v : visits) {
            if (v.node < 0) continue;
            const NodeRecord& n = nodes[std::size_t(v.node)];
            const bool on_path = hit_path.count(v.node) > 0;
            draw_box_overlay(*a, n.box,
                             on_path ? IM_COL32(255, 230, 60, 255) : IM_COL32(150, 150, 150, 160),
                             on_path ? 2.0f : 1.0f);
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Text("%u", unsigned(v.depth));
            ImGui::TableNextColumn();
            ImGui::Text("%d%s", v.node, on_path ? " *" : "");
            ImGui::TableNextColumn();
            ImGui::Text("%u/%u", n.rays, n.triangles);
            ImGui::TableNextColumn();
            if (v.leaf) {
                ImGui::TextUnformatted(v.hit_here ? "leaf: found its hit" : "leaf: nothing closer");
                continue;
            }
            const int first = v.first_side_right ? 1 : 0;
            const char* sides[] = {"left", "right"};
            std::string what = std::string(sides[first]) + " first";
            if (on_path) {
                const std::int32_t hit_child =
                    n.children[0] >= 0 && hit_path.count(n.children[0])
                        ? 0
                        : (n.children[1] >= 0 && hit_path.count(n.children[1]) ? 1 : -1);
                if (hit_child >= 0) {
                    what += hit_child == first ? " (right choice)" : " (order miss)";
                    order_misses += hit_child != first;
                }
            }
            for (int side : {first, 1 - first})
                what += std::string("; ") + sides[side] + ": " +
                        (v.passed[side] ? (n.filter_skipped[side] ? "passed unfiltered" : "kept")
                                        : "filtered out");
            ImGui::TextUnformatted(what.c_str());
        }
        ImGui::EndTable();
    }
    ImGui::Text("%zu nodes entered, %d order misses; * = on the path to the hit", visits.size(),
                order_misses);
    // Mark the pixel.
    const float sx = display.x / float(a->width), sy = display.y / float(a->height);
    ImGui::GetBackgroundDrawList()->AddCircle(
        ImVec2((float(x) + 0.5f) * sx, (float(y) + 0.5f) * sy), 8.0f, IM_COL32(255, 60, 200, 255),
        0, 2.0f);
    ImGui::End();
}

}  // namespace edacrt::app
