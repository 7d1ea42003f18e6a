// Statistics tab: per-level statistics of the camera rays of the first full-resolution pass
// (the batch the heat maps, the explorer and the debugger show): a table, bar charts, totals
// and per-ray means; and every method timed on the view's camera rays.
#include <imgui.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include "panels.h"
#include "viewer_jobs.h"

namespace edacrt::app {
namespace {

/// One bar chart per level of a per-level value.
void bars(const char* label, const std::vector<LevelStats>& levels, float width,
          double (*value)(const LevelStats&)) {
    std::vector<float> values;
    for (const LevelStats& level : levels) values.push_back(float(value(level)));
    ImGui::PlotHistogram(label, values.data(), int(values.size()), 0, nullptr, 0.0f, FLT_MAX,
                         ImVec2(width, 56));
}

/// The per-level charts, two to a row: what each level of the recursion spends.
void level_charts(const std::vector<LevelStats>& levels) {
    ImGui::TextDisabled("per level, from the root (left) down:");
    // Two charts and their labels to a row.
    const float label = ImGui::CalcTextSize("sampling box tests").x + 16.0f;
    const float width = std::clamp(ImGui::GetContentRegionAvail().x * 0.5f - label, 80.0f, 420.0f);
    bars("rays in", levels, width, [](const LevelStats& l) { return double(l.rays_in); });
    ImGui::SameLine();
    bars("triangle tests", levels, width,
         [](const LevelStats& l) { return double(l.ray_triangle_tests); });
    bars("sampling box tests", levels, width,
         [](const LevelStats& l) { return double(l.sample_box_tests); });
    ImGui::SameLine();
    bars("filter box tests", levels, width,
         [](const LevelStats& l) { return double(l.filter_box_tests); });
    bars("ms", levels, width, [](const LevelStats& l) { return l.seconds() * 1e3; });
}

/// Per level, how far each split child's estimated alpha is from the share of the node's rays
/// that hit it: the level means in the table above hide single nodes far off. Click a row for
/// its histogram.
void alpha_errors(const std::vector<LevelStats>& levels) {
    int& selected = *ImGui::GetStateStorage()->GetIntRef(ImGui::GetID("alpha error level"));
    ImGui::TextDisabled("alpha error |estimated - true| per split child; nodes by alpha source:");
    const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                  ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit;
    const float rows = float(levels.size() + 2) * ImGui::GetTextLineHeightWithSpacing();
    if (ImGui::BeginTable("alpha errors", int(alpha_error_columns().size()), flags,
                          ImVec2(0, std::min(rows, 160.0f)))) {
        table_headers(alpha_error_columns(), 1);
        for (std::size_t i = 0; i < levels.size(); ++i) {
            const LevelStats& l = levels[i];
            if (l.alpha_children == 0) continue;
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            if (ImGui::Selectable(std::to_string(i).c_str(), selected == int(i),
                                  ImGuiSelectableFlags_SpanAllColumns))
                selected = int(i);
            for (const std::uint64_t n : l.alpha_sources) {
                ImGui::TableNextColumn();
                cell_text("%llu", static_cast<unsigned long long>(n));
            }
            ImGui::TableNextColumn();
            cell_text("%.1f",
                      double(l.sampled_rays) / double(std::max<std::uint64_t>(l.sampled_nodes, 1)));
            for (const double e :
                 {l.alpha_error_sum / double(l.alpha_children), l.alpha_error_quantile(0.5),
                  l.alpha_error_quantile(0.9), l.alpha_error_max}) {
                ImGui::TableNextColumn();
                cell_text("%.3f", e);
            }
        }
        ImGui::EndTable();
    }
    if (selected >= int(levels.size())) return;
    const LevelStats& l = levels[std::size_t(selected)];
    float counts[kAlphaErrorBins];
    std::copy(std::begin(l.alpha_error_bins), std::end(l.alpha_error_bins), counts);
    const std::string label =
        "level " + std::to_string(selected) + ": children per 0.01 of error, 0 to 1";
    ImGui::PlotHistogram("##alpha error histogram", counts, kAlphaErrorBins, 0, label.c_str(), 0.0f,
                         FLT_MAX, ImVec2(std::min(ImGui::GetContentRegionAvail().x, 600.0f), 56));
}

}  // namespace

/// Every method on the view's camera rays (pixel centres, or jittered rays per pixel), the
/// render paused meanwhile.
void draw_comparison(ViewerState& s) {
    ImGui::Separator();
    if (ImGui::Button(s.comparing ? "comparing..." : "compare methods") && !s.comparing)
        s.compare_requested = true;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::CalcTextSize("16 spp").x + ImGui::GetFrameHeight() * 2.0f);
    setting_widget(s, "compare-spp", {"##compare spp"});
    ImGui::SameLine();
    ImGui::TextDisabled(s.playback.frames
                            ? "this frame's camera rays, every method and update, median of 3 "
                              "(render paused)"
                            : "the view's camera rays, every method, median of 3 (render paused)");
    if (s.comparison.empty() || s.compared_scene != s.scene_number) return;  // another scene's
    ImGui::TextDisabled("measured on %d camera ray%s per pixel", s.comparison.front().spp,
                        s.comparison.front().spp == 1 ? "" : "s");
    if (s.playback.frames)
        ImGui::TextDisabled(
            "measured at t = %.3f s; refit and dynamic start from the frame 1/24 s before",
            s.playback.compared_time);
    const MethodTotals* embree = nullptr;
    for (const MethodTotals& m : s.comparison)
        if (m.method == Method::embree && m.update == SceneUpdate::rebuild && m.error.empty())
            embree = &m;
    const ImGuiTableFlags flags =
        ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX;
    const float height = float(s.comparison.size() + 2) * ImGui::GetFrameHeightWithSpacing();
    if (!ImGui::BeginTable("compare", int(comparison_columns().size()), flags, ImVec2(0, height)))
        return;
    table_headers(comparison_columns());
    for (const MethodTotals& m : s.comparison) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        cell_text("%s", std::string(enum_name(kMethods, m.method)).c_str());
        ImGui::TableNextColumn();
        // Methods without a structure have nothing to refit: their update is per-frame data.
        const bool structure = m.method == Method::bvh || m.method == Method::embree;
        cell_text("%s",
                  structure ? std::string(enum_name(kSceneUpdates, m.update)).c_str() : "none");
        ImGui::TableNextColumn();
        if (!m.error.empty()) {
            cell_text("%s", m.error.c_str());
            continue;
        }
        const double n = double(std::max<std::uint64_t>(m.stats.rays, 1));
        cell_text("%.1f", m.update_seconds * 1e3);
        ImGui::TableNextColumn();
        cell_text("%.1f", m.seconds * 1e3);
        ImGui::TableNextColumn();
        cell_text("%.1f", m.seconds > 0 ? n / m.seconds * 1e-6 : 0.0);
        ImGui::TableNextColumn();
        embree ? cell_text("%.2fx", m.seconds / std::max(embree->seconds, 1e-12))
               : cell_text("n/a");
        // Embree does not count its tests.
        for (std::uint64_t tests : {m.stats.ray_box_tests, m.stats.ray_triangle_tests}) {
            ImGui::TableNextColumn();
            m.method == Method::embree ? cell_text("n/a") : cell_text("%.1f", double(tests) / n);
        }
    }
    ImGui::EndTable();
}

void draw_stats_tab(ViewerState& s) {
    const ShownBatch batch = shown_batch(s);
    const TraceDetail* detail = batch.detail;
    if (!detail) {
        ImGui::TextDisabled(s.batch == BatchId{} ? "waiting for the first full-resolution pass"
                                                 : "waiting for the batch's recording");
        draw_comparison(s);
        return;
    }
    const auto& levels = detail->levels;
    std::uint64_t box = 0, tri = 0;
    for (const RayStats& r : detail->rays) {
        box += r.ray_box_tests;
        tri += r.ray_triangle_tests;
    }
    const double rays = double(std::max<std::size_t>(detail->rays.size(), 1));
    if (s.batch == BatchId{})
        ImGui::Text("%s: the first pass's %zu camera rays (%dx%d, 1 per pixel), one batch",
                    std::string(enum_name(kMethods, s.submitted.method)).c_str(),
                    detail->rays.size(), batch.width, batch.height);
    else
        ImGui::Text("%s: the first pass's %zu %s rays (%dx%d%s), one batch",
                    std::string(enum_name(kMethods, s.submitted.method)).c_str(),
                    detail->rays.size(), batch_name(s.batch).c_str(), batch.width, batch.height,
                    s.analysis->cropped() ? (", the " + region_name(*s.analysis)).c_str() : "");
    ImGui::Text("%.1f ray-box and %.1f ray-triangle tests per ray", double(box) / rays,
                double(tri) / rays);
    if (!levels.empty())
        ImGui::Text("one recursion; %llu rays entered the scene box",
                    static_cast<unsigned long long>(detail->root.entered));
    if (levels.empty()) {
        ImGui::TextDisabled("(%s has no recursion levels)",
                            std::string(enum_name(kMethods, s.ui.method)).c_str());
    } else {
        const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                      ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX |
                                      ImGuiTableFlags_SizingFixedFit;
        const float rows = float(levels.size() + 3) * ImGui::GetTextLineHeightWithSpacing();
        ImGui::Checkbox("all columns", &s.all_columns);
        wrapped_tooltip(
            "off: the compact set that fits the default window (leaves, rays down, "
            "filtered, 2nd split, order 1st and culled left out)");
        if (ImGui::BeginTable("levels", int(level_columns().size()), flags,
                              ImVec2(0, std::min(rows, 220.0f)))) {
            // The total first, under the header. Not frozen with it: ImGui 1.86 fits the
            // columns without a frozen row's text (a total of 10.82 ms was clipped).
            table_headers(level_columns(), 1, !s.all_columns);
            const auto count = [](std::uint64_t v) {
                ImGui::TableNextColumn();
                cell_text("%llu", static_cast<unsigned long long>(v));
            };
            LevelStats total;
            for (const LevelStats& l : levels) total += l;
            // The total, the root filter (the batch against the scene box: rays in, rays
            // down, filter box tests and time; the other columns do not apply), the levels.
            for (std::size_t row = 0; row < levels.size() + 2; ++row) {
                if (row == 1) {
                    const RootStats& root = detail->root;
                    ImGui::TableNextRow();
                    ImGui::TableNextColumn();
                    cell_text("scene box");
                    ImGui::TableSetColumnIndex(3);
                    cell_text("%llu", static_cast<unsigned long long>(root.rays));
                    count(root.entered);
                    ImGui::TableSetColumnIndex(10);
                    cell_text("%llu", static_cast<unsigned long long>(root.box_tests));
                    ImGui::TableSetColumnIndex(16);
                    cell_text("%.2f", root.seconds * 1e3);
                    continue;
                }
                const bool is_total = row == 0;
                const LevelStats& l = is_total ? total : levels[row - 2];
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                is_total ? cell_text("total") : cell_text("%zu", row - 2);
                for (std::uint64_t v :
                     {l.nodes, l.leaves, l.rays_in, l.rays_passed, l.filters_done,
                      l.filters_skipped, l.second_splits, l.triangles, l.sample_box_tests,
                      l.filter_box_tests, l.ray_triangle_tests})
                    count(v);
                ImGui::TableNextColumn();
                const std::uint64_t ordered = l.order_hits + l.order_misses;
                if (ordered > 0)
                    cell_text("%.0f%%", 100.0 * double(l.order_hits) / double(ordered));
                count(l.culled_by_distance);
                const double children = double(std::max<std::uint64_t>(l.alpha_children, 1));
                ImGui::TableNextColumn();
                cell_text("%.2f", l.alpha_estimated_sum / children);
                ImGui::TableNextColumn();
                cell_text("%.2f", l.alpha_true_sum / children);
                ImGui::TableNextColumn();
                cell_text("%.2f", l.seconds() * 1e3);
            }
            ImGui::EndTable();
        }
        level_charts(levels);
        alpha_errors(levels);
    }

    draw_comparison(s);
}

}  // namespace edacrt::app
