// Traversal tab, the debugger: click a pixel to follow its ray in the chosen batch (the camera
// ray, a bounce, a shadow ray: the batch chooser's arrows step along the pixel's path) through
// the recursion: the nodes it entered, which child went first and whether that was the one
// holding the final hit, where it was filtered out or passed down unfiltered, and the leaf that
// produced the hit.
#include <imgui.h>

#include <algorithm>
#include <set>

#include "geometry/ray_box.h"
#include "panels.h"

namespace edacrt::app {

void draw_traversal_tab(ViewerState& s) {
    ImGui::Checkbox("pick pixels (click the image; stays on, drags still orbit)", &s.picking);
    const Analysis* a = s.analysis.get();
    if (!a || a->pixel < 0 || !a->detail) {
        ImGui::TextDisabled(s.analysis_running ? "tracing..." : "no pixel followed yet");
        return;
    }
    if (s.analysis_stale) {
        ImGui::TextColored(ImVec4(1, 0.7f, 0.3f, 1),
                           "stale: followed in another view, scene or parameters; boxes hidden");
        ImGui::SameLine();
        if (ImGui::SmallButton("follow again")) s.analysis_requested = true;
    }
    const auto& nodes = a->detail->nodes;
    const auto& visits = a->detail->follow;
    const int x = int(a->pixel % a->width), y = int(a->pixel / a->width);
    if (!a->followed) {
        // Outside the crop, or the pixel's path made no ray of this batch.
        const bool in_crop = x >= a->crop_x && y >= a->crop_y && x < a->crop_x + a->crop_w &&
                             y < a->crop_y + a->crop_h;
        ImGui::Text("pixel (%d, %d): no %s ray %s", x, y, batch_name(a->batch).c_str(),
                    in_crop ? "(its path ended before)"
                            : "in the recorded batch: it lies outside the recorded region");
        return;
    }
    const bool any = batch_query(a->batch) == Query::any;
    ImGui::Text(
        "pixel (%d, %d), its %s ray: %s", x, y, batch_name(a->batch).c_str(),
        !a->hit.hit() ? (any ? "unoccluded" : "no hit")
        : any         ? ("occluded by triangle " + std::to_string(a->hit.prim)).c_str()
              : ("triangle " + std::to_string(a->hit.prim) + " at t = " + std::to_string(a->hit.t))
                    .c_str());
    if (visits.empty()) {
        ImGui::TextDisabled("(%s records no recursion, or the ray missed the scene's box)",
                            std::string(enum_name(kMethods, a->method)).c_str());
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
    const SlabRay slab = make_slab_ray(a->ray);
    if (ImGui::BeginTable("visits", int(visit_columns().size()),
                          ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollY |
                              ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX,
                          ImVec2(0, std::max(ImGui::GetContentRegionAvail().y -
                                                 ImGui::GetTextLineHeightWithSpacing() - 4.0f,
                                             120.0f)))) {
        table_headers(visit_columns());
        for (const RayVisit& v : visits) {
            if (v.node < 0) continue;
            const NodeRecord& n = nodes[std::size_t(v.node)];
            const bool on_path = hit_path.count(v.node) > 0;
            draw_box_overlay(s, *a, n.box,
                             on_path ? IM_COL32(255, 230, 60, 255) : IM_COL32(150, 150, 150, 160),
                             on_path ? 2.0f : 1.0f);
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            cell_text("%u", unsigned(v.depth));
            ImGui::TableNextColumn();
            cell_text("%d%s", v.node, on_path ? " *" : "");
            ImGui::TableNextColumn();
            v.leaf ? cell_text("%u", n.rays)
                   : cell_text("%u/%u+%u", n.rays, n.rays_passed[0], n.rays_passed[1]);
            ImGui::TableNextColumn();
            cell_text("%u", n.triangles);
            ImGui::TableNextColumn();
            if (v.leaf) {
                ImGui::TableNextColumn();
                cell_text("leaf: %u tests", n.triangles);
                ImGui::TableNextColumn();
                cell_text("%s", v.hit_here ? "found its hit" : "nothing closer");
                continue;
            }
            cell_text("%.2f/%.2f", n.alpha_true[0], n.alpha_true[1]);
            ImGui::TableNextColumn();
            const int first = v.first_side_right ? 1 : 0;
            cell_text("%s", first ? "right" : "left");
            ImGui::TableNextColumn();
            if (on_path) {
                const std::int32_t hit_child =
                    n.children[0] >= 0 && hit_path.count(n.children[0])
                        ? 0
                        : (n.children[1] >= 0 && hit_path.count(n.children[1]) ? 1 : -1);
                if (hit_child >= 0) {
                    cell_text("%s", hit_child == first ? "right choice" : "order miss");
                    order_misses += hit_child != first;
                }
            }
            for (int side : {0, 1}) {
                ImGui::TableNextColumn();
                if (v.passed[side]) {
                    cell_text("%s", n.filter_skipped[side] ? "passed unfiltered" : "kept");
                    continue;
                }
                // Filtered out: it misses the child's box, or meets it only beyond the hit
                // found so far (culled by distance).
                const CandidateSplit& c = n.candidates[std::size_t(n.chosen)];
                float entry = 0.0f;
                const bool meets =
                    intersect_box(slab, side == 0 ? c.left : c.right, a->ray.tmax, entry);
                cell_text("%s", meets ? "culled by distance" : "filtered out (misses)");
            }
        }
        ImGui::EndTable();
    }
    ImGui::Text("%zu nodes entered, %d order misses; * = on the path to the hit", visits.size(),
                order_misses);
    // Mark the pixel.
    if (!s.analysis_stale)
        ImGui::GetBackgroundDrawList()->AddCircle(
            image_to_window(s, float(x) + 0.5f, float(y) + 0.5f, a->width, a->height), 8.0f,
            IM_COL32(255, 60, 200, 255), 0, 2.0f);
}

}  // namespace edacrt::app
