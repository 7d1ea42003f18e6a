// Recursion tab, the explorer (teaching): the boxes of one level of the current view's recursion
// over the image, each node's rays, triangles and cost; a node's K - 1 candidate splits with their
// costs and the chosen one.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "panels.h"
#include "util/hash_random.h"
#include "viewer_jobs.h"

namespace edacrt::app {
namespace {

unsigned node_colour(std::size_t node, float alpha = 1.0f) {
    const glm::vec3 c = turbo(0.1f + 0.8f * hash_to_unit_float(pcg_hash(std::uint32_t(node))));
    return ImGui::GetColorU32(ImVec4(c.x, c.y, c.z, alpha));
}

/// Where a split node's alpha came from: "sampled (6 rays)", "area", "every ray (24 rays)".
std::string alpha_source(const NodeRecord& node) {
    std::string text(enum_name(kAlphaSources, node.alpha_source));
    if (node.alpha_source != AlphaSource::area)
        text += " (" + std::to_string(node.samples) + " rays)";
    return text;
}

void candidates_table(ViewerState& s, const NodeRecord& node, const EdacrtParams& params) {
    ImGui::Text("node %d: %u rays, %u triangles, split along %c; alpha %s", s.explorer_node,
                node.rays, node.triangles, "xyz"[std::max(node.axis, 0)],
                alpha_source(node).c_str());
    // A leaf's cost decides only where the cost-leaf test looks at the node.
    if (cost_leaf_tested(params, node.triangles)) {
        ImGui::SameLine(0.0f, 0.0f);
        ImGui::Text("; leaf cost %.1f", node.leaf_cost);
    }
    s.hovered_candidate = -1;
    const float height = float(node.candidates.size() + 1) * ImGui::GetTextLineHeightWithSpacing() +
                         2.0f * ImGui::GetStyle().CellPadding.y * float(node.candidates.size() + 1);
    if (!ImGui::BeginTable("candidates", int(candidate_columns().size()),
                           ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                               ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX,
                           ImVec2(0, height + 4.0f)))
        return;
    table_headers(candidate_columns());
    for (std::size_t j = 0; j < node.candidates.size(); ++j) {
        const CandidateSplit& c = node.candidates[j];
        ImGui::TableNextRow();
        if (std::int32_t(j) == node.chosen)
            ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg0, IM_COL32(40, 110, 60, 255));
        ImGui::TableNextColumn();
        cell_text("%zu%s", j, std::int32_t(j) == node.chosen ? " *" : "");
        if (ImGui::IsItemHovered()) s.hovered_candidate = std::int32_t(j);
        ImGui::TableNextColumn();
        cell_text("%u", c.left_triangles);
        ImGui::TableNextColumn();
        cell_text("%u", c.right_triangles);
        ImGui::TableNextColumn();
        cell_text("%.3f", c.alpha_left);
        ImGui::TableNextColumn();
        cell_text("%.3f", c.alpha_right);
        ImGui::TableNextColumn();
        std::isfinite(c.cost) ? cell_text("%.1f", c.cost) : cell_text("(empty)");
    }
    ImGui::EndTable();
    ImGui::TextDisabled(
        "cost = C_T + C_I (a_L N_L + a_R N_R); * = chosen; hover a row: its "
        "two child boxes; the candidate planes are drawn on the image");
    if (node.chosen < 0) return;
    // How good the estimate was (the share of all the node's rays that hit each chosen
    // child), and the filter-skip decision (Section 3.4) it led to.
    const CandidateSplit& c = node.candidates[std::size_t(node.chosen)];
    ImGui::Text("%s child first", node.left_first ? "left" : "right");
    const char* sides[] = {"left", "right"};
    const std::string source = alpha_source(node);
    for (int side : {0, 1}) {
        const float estimated = side == 0 ? c.alpha_left : c.alpha_right;
        const std::uint32_t n = side == 0 ? c.left_triangles : c.right_triangles;
        const float threshold = filter_skip_threshold(params, n, node.rays);
        char text[48] = "never (filter skipping off)";
        if (threshold <= 1.0f) std::snprintf(text, sizeof text, "%.3f", threshold);
        // Near the root the first child is filtered whatever its alpha when the rays it
        // rejects make a task for the second child (Recursion::forgoes_task).
        const bool for_task = !node.filter_skipped[side] && estimated > threshold;
        ImGui::TextWrapped(
            "%s: alpha %s %.3f, true %.3f, error %.3f; skip above 1 - C_bv/(n_child C_child) "
            "= %s: %s",
            sides[side], source.c_str(), estimated, node.alpha_true[side], node.alpha_error(side),
            text,
            node.filter_skipped[side] ? "passed unfiltered"
            : for_task ? "filtered, so that the rays it rejects make the second child's task"
                       : "filtered");
    }
}

/// Which part of its parent's split second child a node is, if any.
const char* second_part(const std::vector<NodeRecord>& nodes, std::int32_t node) {
    const NodeRecord& parent = nodes[std::size_t(nodes[std::size_t(node)].parent)];
    if (parent.second_early < 0) return "";
    if (parent.second_early == node)
        return "(second child, early part: the rays that missed the first child's box)";
    if (parent.children[parent.left_first ? 1 : 0] == node)
        return "(second child, late part: the rays that reached the first child's box)";
    return "";
}

/// Step-through: the nodes in the order the recursion entered them (near child first); the
/// node's rays tinted yellow, the pixels whose hit has been found so far green.
void step_through(ViewerState& s, const Analysis& a) {
    const auto& nodes = a.detail->nodes;
    if (!ImGui::Checkbox("step through the recursion", &s.stepping) && !s.stepping) return;
    const int last = int(nodes.size()) - 1;
    s.step = std::clamp(s.step, 0, last);
    if (ImGui::ArrowButton("##back", ImGuiDir_Left)) s.step = std::max(0, s.step - 1);
    ImGui::SameLine();
    if (ImGui::ArrowButton("##next", ImGuiDir_Right)) s.step = std::min(last, s.step + 1);
    ImGui::SameLine();
    // Auto-play; started at the last node, from the first again.
    if (setting_widget(s, "step-play") && s.step_playing && s.step == last) s.step = 0;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 7);
    setting_widget(s, "step-rate", {"##step-rate", "%.3g nodes/s"});
    s.step = advance_step(s.step, last, s.step_rate, ImGui::GetIO().DeltaTime, s.step_carry,
                          s.step_playing);
    ImGui::SetNextItemWidth(-1.0f);
    ImGui::SliderInt("##step", &s.step, 0, last, "node %d");
    const NodeRecord& n = nodes[std::size_t(s.step)];
    std::size_t found = 0;
    for (const std::int32_t h : a.detail->hit_node) found += h >= 0 && h <= s.step;
    ImGui::TextWrapped(
        "node %d of %zu, depth %u: %u rays x %u triangles, %s; hits found so far: "
        "%zu of %zu rays (green); this node's rays yellow",
        s.step, nodes.size(), unsigned(n.depth), n.rays, n.triangles,
        n.leaf ? "a leaf (brute force)" : "split", found, a.detail->hit_node.size());
    s.explorer_node = s.step;
}

/// The combo of the recursion the recording is compared with: none, or a preset.
void against_combo(ViewerState& s) {
    ImGui::SetNextItemWidth(ImGui::CalcTextSize("default").x + ImGui::GetFrameHeight() * 2.0f);
    if (ImGui::BeginCombo("against", s.against.empty() ? "none" : s.against.c_str())) {
        std::vector<std::string> choices = {"none"};
        for (const std::string_view name : preset_names()) choices.emplace_back(name);
        for (const std::string& name : choices) {
            const std::string value = name == "none" ? "" : name;
            if (ImGui::Selectable(name.c_str(), s.against == value)) {
                s.against = value;
                s.analysis_requested = true;
            }
        }
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "records the same rays again by EDACRT with this preset (B; dacrt: DACRT as Mora "
            "2011 / Afra 2012 define it) beside the recording (A: the method and parameters "
            "in force): their levels side by side, and the nodes where their decisions first "
            "differ (`set against PRESET|none`)");
}

/// A and B level by level (tests per ray of the batch), and the node pairs where the two
/// recursions first decide differently; a click selects A's node.
void against_tables(ViewerState& s, const Analysis& a) {
    const TraceDetail &da = *a.detail, &db = *a.against_detail;
    const double rays = double(std::max<std::size_t>(1, da.rays.size()));
    ImGui::Text("A: %s, B: EDACRT with the %s preset, on the same %zu rays",
                std::string(enum_name(kMethods, a.method)).c_str(), a.against.c_str(),
                da.rays.size());
    const std::size_t levels = std::max(da.levels.size(), db.levels.size());
    if (ImGui::BeginTable("against", int(against_columns().size()),
                          ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollY |
                              ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX,
                          ImVec2(0, 8.0f * ImGui::GetFrameHeightWithSpacing()))) {
        table_headers(against_columns(), 1);
        LevelStats ta, tb;
        const auto row = [&](const char* label, const LevelStats* la, const LevelStats* lb) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            cell_text("%s", label);
            for (const LevelStats* l : {la, lb}) {
                ImGui::TableNextColumn();
                if (l) cell_text("%llu", (unsigned long long)l->nodes);
            }
            for (int box = 1; box >= 0; --box)
                for (const LevelStats* l : {la, lb}) {
                    ImGui::TableNextColumn();
                    if (l)
                        cell_text("%.2f",
                                  double(box ? l->ray_box_tests : l->ray_triangle_tests) / rays);
                }
        };
        const auto add = [](LevelStats& t, const LevelStats& l) {
            t.nodes += l.nodes;
            t.ray_box_tests += l.ray_box_tests;
            t.ray_triangle_tests += l.ray_triangle_tests;
        };
        for (std::size_t i = 0; i < levels; ++i) {
            const LevelStats* la = i < da.levels.size() ? &da.levels[i] : nullptr;
            const LevelStats* lb = i < db.levels.size() ? &db.levels[i] : nullptr;
            if (la) add(ta, *la);
            if (lb) add(tb, *lb);
            row(std::to_string(i).c_str(), la, lb);
        }
        row("total", &ta, &tb);
        ImGui::EndTable();
    }
    if (a.differences.empty()) {
        ImGui::TextDisabled("the two recursions decide alike at every node recorded in both");
        return;
    }
    ImGui::Text("decisions first differ at %zu node%s%s (A's node, B's, depth):",
                a.differences.size(), a.differences.size() == 1 ? "" : "s",
                a.differences.size() >= 200 ? " (the first 200)" : "");
    if (ImGui::BeginChild("differences", ImVec2(0, 5.0f * ImGui::GetTextLineHeightWithSpacing()),
                          true)) {
        for (const DecisionDifference& d : a.differences) {
            const std::string line = "node " + std::to_string(d.node_a) + " / " +
                                     std::to_string(d.node_b) + ", depth " +
                                     std::to_string(d.depth) + ": " + d.what;
            if (ImGui::Selectable(line.c_str(), s.explorer_node == d.node_a)) {
                s.explorer_node = d.node_a;
                s.explorer_level = d.depth;
                s.stepping = false;
            }
        }
    }
    ImGui::EndChild();
}

}  // namespace

void draw_recursion_tab(ViewerState& s) {
    s.recursion_shown = true;
    if (ImGui::Button(s.analysis_running ? "recording..." : "record")) s.analysis_requested = true;
    ImGui::SameLine();
    if (ImGui::RadioButton("the whole batch", !s.explorer_crop)) s.explorer_crop = false;
    ImGui::SameLine();
    if (ImGui::RadioButton("a region (to step through)", s.explorer_crop)) s.explorer_crop = true;
    ImGui::SameLine();
    if (ImGui::Button(s.region_picking ? "drag on the image..." : "drag a region"))
        s.region_picking = !s.region_picking;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "the next left drag on the image chooses the region, instead of moving the camera "
            "(without one: 64x64 pixels at the centre); `set region U0,V0,U1,V1` in a script");
    ImGui::SameLine();
    ImGui::Checkbox("tint pixels", &s.explorer_tint);
    ImGui::SameLine();
    against_combo(s);
    const Analysis* a = s.analysis.get();
    if (!a || !a->error.empty() || !a->detail || a->detail->nodes.empty()) {
        if (a && !a->error.empty())
            ImGui::TextWrapped("%s", a->error.c_str());
        else if (a)
            ImGui::TextDisabled("(%s records no recursion)",
                                std::string(enum_name(kMethods, a->method)).c_str());
        return;
    }
    if (s.analysis_stale) {
        ImGui::TextColored(ImVec4(1, 0.7f, 0.3f, 1),
                           "stale: recorded for another view, scene or parameters; boxes hidden");
        ImGui::SameLine();
        if (ImGui::SmallButton("re-record")) s.analysis_requested = true;
    }
    ImGui::TextDisabled("recorded: %zu %s rays of the first pass (%s), %zu nodes",
                        a->detail->rays.size(), batch_name(a->batch).c_str(),
                        a->cropped()
                            ? ("those in the " + region_name(*a) + ", a batch of their own").c_str()
                            : "the whole view, the Statistics tab's batch",
                        a->detail->nodes.size());
    if (a->against_detail && ImGui::CollapsingHeader("A against B", ImGuiTreeNodeFlags_DefaultOpen))
        against_tables(s, *a);
    step_through(s, *a);
    const auto& nodes = a->detail->nodes;
    int deepest = 0;
    for (const NodeRecord& n : nodes) deepest = std::max(deepest, int(n.depth));
    ImGui::SliderInt("level", &s.explorer_level, 0, deepest);
    ImGui::SameLine();
    if (ImGui::ArrowButton("##down", ImGuiDir_Left))
        s.explorer_level = std::max(0, s.explorer_level - 1);
    ImGui::SameLine();
    if (ImGui::ArrowButton("##up", ImGuiDir_Right))
        s.explorer_level = std::min(deepest, s.explorer_level + 1);

    // The level's nodes: boxes over the image, and a list to pick one from.
    std::size_t shown = 0;
    if (ImGui::BeginTable("nodes", int(node_columns().size()),
                          ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollY |
                              ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX,
                          ImVec2(0, 130))) {
        table_headers(node_columns());
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            const NodeRecord& n = nodes[i];
            if (n.depth != s.explorer_level) continue;
            if (shown++ < 4000) draw_box_overlay(s, *a, n.box, node_colour(i, 0.8f));
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::PushStyleColor(ImGuiCol_Text, node_colour(i));
            if (ImGui::Selectable(std::to_string(i).c_str(), s.explorer_node == std::int32_t(i),
                                  ImGuiSelectableFlags_SpanAllColumns))
                s.explorer_node = std::int32_t(i);
            ImGui::PopStyleColor();
            if (ImGui::IsItemHovered())
                draw_box_overlay(s, *a, n.box, IM_COL32(255, 255, 255, 255), 3);
            ImGui::TableNextColumn();
            cell_text("%u", n.rays);
            ImGui::TableNextColumn();
            cell_text("%u", n.triangles);
            ImGui::TableNextColumn();
            cell_text("%s", n.leaf ? "leaf" : n.left_first ? "split, L first" : "split, R first");
            ImGui::TableNextColumn();
            if (n.leaf) continue;
            cell_text("%s/%s", n.filter_skipped[0] ? "skip" : "filt",
                      n.filter_skipped[1] ? "skip" : "filt");
            ImGui::TableNextColumn();
            cell_text("%s", alpha_source(n).c_str());
            ImGui::TableNextColumn();
            cell_text("%.3f", std::max(n.alpha_error(0), n.alpha_error(1)));
        }
        ImGui::EndTable();
    }
    ImGui::Text("%zu nodes at level %d (%zu recorded in all)", shown, s.explorer_level,
                nodes.size());

    // The selected node's candidate splits; the chosen (or hovered) one drawn as two boxes.
    if (s.explorer_node >= 0 && std::size_t(s.explorer_node) < nodes.size()) {
        const NodeRecord& node = nodes[std::size_t(s.explorer_node)];
        ImGui::Separator();
        draw_box_overlay(s, *a, node.box, IM_COL32(255, 255, 255, 255), 2.0f);
        if (node.leaf) {
            ImGui::Text("node %d is a leaf: %u rays x %u triangles, brute force", s.explorer_node,
                        node.rays, node.triangles);
        } else {
            candidates_table(s, node, a->params);
            // The K - 1 candidate planes across the node's box, the chosen one brighter.
            for (std::size_t k = 0; k < node.candidates.size(); ++k) {
                Aabb plane = node.box;
                plane.lo[node.axis] = plane.hi[node.axis] = node.candidates[k].plane;
                const bool chosen = std::int32_t(k) == node.chosen;
                draw_box_overlay(
                    s, *a, plane,
                    chosen ? IM_COL32(255, 255, 255, 220) : IM_COL32(120, 200, 255, 110),
                    chosen ? 2.0f : 1.0f);
            }
            const std::int32_t j = s.hovered_candidate >= 0 ? s.hovered_candidate : node.chosen;
            const CandidateSplit& c = node.candidates[std::size_t(j)];
            draw_box_overlay(s, *a, c.left, IM_COL32(80, 230, 120, 255), 2.0f);
            draw_box_overlay(s, *a, c.right, IM_COL32(255, 150, 40, 255), 2.0f);
        }
        if (node.parent >= 0) {
            if (ImGui::Button("parent")) s.explorer_node = node.parent;
            ImGui::SameLine();
            ImGui::TextDisabled("%s", second_part(nodes, s.explorer_node));
        }
        // A split second child: children[] holds its part entered after the first child.
        const int second_side = node.left_first ? 1 : 0;
        for (int side : {0, 1})
            if (node.children[side] >= 0) {
                ImGui::SameLine();
                const bool late = node.second_early >= 0 && side == second_side;
                if (ImGui::Button(side == 0 ? (late ? "left child, late part" : "left child")
                                            : (late ? "right child, late part" : "right child")))
                    s.explorer_node = node.children[side];
            }
        if (node.second_early >= 0) {
            ImGui::SameLine();
            if (ImGui::Button("second child, early part")) s.explorer_node = node.second_early;
            wrapped_tooltip(
                "second-child split: the rays that missed the first child's box went to the "
                "second child at once, beside the first child (this part); the rest once the "
                "first child was done (the late part)");
        }
        if (s.explorer_node >= 0) s.explorer_level = nodes[std::size_t(s.explorer_node)].depth;
    }
}

}  // namespace edacrt::app
