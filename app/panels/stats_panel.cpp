// Per-level statistics of the camera rays of the first full-resolution pass: a table, bar
// charts, totals and per-ray means, and the same totals for the other methods.
#include <imgui.h>

#include <vector>

#include "viewer_state.h"

namespace edacrt::app {
namespace {

void bars(const char* label, const std::vector<LevelStats>& levels,
          std::uint64_t LevelStats::*field) {
    std::vector<float> values;
    for (const LevelStats& level : levels) values.push_back(float(level.*field));
    ImGui::PlotHistogram(label, values.data(), int(values.size()), 0, nullptr, 0.0f, FLT_MAX,
                         ImVec2(0, 60));
}

}  // namespace

void draw_stats_panel(ViewerState& s) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x - 640, display.y - 390), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(630, 380), ImGuiCond_FirstUseEver);
    ImGui::Begin("Per-level statistics");
    const TraceDetail* detail = s.frame && s.frame->detail ? s.frame->detail.get() : nullptr;
    if (!detail) {
        ImGui::TextDisabled("waiting for the first full-resolution pass");
        ImGui::End();
        return;
    }
    const auto& levels = detail->levels;
    std::uint64_t box = 0, tri = 0;
    for (const RayStats& r : detail->rays) {
        box += r.ray_box_tests;
        tri += r.ray_triangle_tests;
    }
    const double rays = double(std::max<std::size_t>(detail->rays.size(), 1));
    ImGui::Text("%zu camera rays: %.1f ray-box and %.1f ray-triangle tests per ray",
                detail->rays.size(), double(box) / rays, double(tri) / rays);
    if (!levels.empty())
        ImGui::Text("one recursion; %llu rays entered the scene box",
                    static_cast<unsigned long long>(detail->root.entered));
    if (levels.empty()) {
        ImGui::TextDisabled("(%s has no recursion levels)",
                            std::string(method_name(s.ui.method)).c_str());
    } else {
        const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                      ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX |
                                      ImGuiTableFlags_SizingFixedFit;
        // Order: of the rays that hit both children's boxes and found their hit below, the
        // share whose hit was in the child visited first. alpha: estimated / true hit ratio.
        const char* headers[] = {"level",      "nodes",      "leaves",     "rays in",
                                 "rays down",  "filtered",   "skipped",    "tris",
                                 "sample box", "filter box", "tri tests",  "order 1st",
                                 "culled",     "alpha est",  "alpha true", "ms"};
        if (ImGui::BeginTable("levels", 16, flags, ImVec2(0, 200))) {
            for (const char* h : headers) ImGui::TableSetupColumn(h);
            ImGui::TableSetupScrollFreeze(1, 1);
            ImGui::TableHeadersRow();
            const auto count = [](std::uint64_t v) {
                ImGui::TableNextColumn();
                ImGui::Text("%llu", static_cast<unsigned long long>(v));
            };
            // The root filter: the batch against the scene box (rays in, rays down, filter
            // box tests and time; the other columns do not apply).
            const RootStats& root = detail->root;
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted("scene box");
            ImGui::TableSetColumnIndex(3);
            ImGui::Text("%llu", static_cast<unsigned long long>(root.rays));
            count(root.entered);
            ImGui::TableSetColumnIndex(9);
            ImGui::Text("%llu", static_cast<unsigned long long>(root.box_tests));
            ImGui::TableSetColumnIndex(15);
            ImGui::Text("%.2f", root.seconds * 1e3);
            LevelStats total;
            for (std::size_t i = 0; i <= levels.size(); ++i) {
                const bool is_total = i == levels.size();
                const LevelStats& l = is_total ? total : levels[i];
                if (!is_total) total += l;
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                is_total ? ImGui::TextUnformatted("total") : ImGui::Text("%zu", i);
                for (std::uint64_t v : {l.nodes, l.leaves, l.rays_in, l.rays_passed, l.filters_done,
                                        l.filters_skipped, l.triangles, l.sample_box_tests,
                                        l.filter_box_tests, l.ray_triangle_tests})
                    count(v);
                ImGui::TableNextColumn();
                const std::uint64_t ordered = l.order_hits + l.order_misses;
                if (ordered > 0)
                    ImGui::Text("%.0f%%", 100.0 * double(l.order_hits) / double(ordered));
                count(l.culled_by_distance);
                const double children = double(std::max<std::uint64_t>(l.alpha_children, 1));
                ImGui::TableNextColumn();
                ImGui::Text("%.2f", l.alpha_estimated_sum / children);
                ImGui::TableNextColumn();
                ImGui::Text("%.2f", l.alpha_true_sum / children);
                ImGui::TableNextColumn();
                ImGui::Text("%.2f", l.seconds() * 1e3);
            }
            ImGui::EndTable();
        }
        bars("rays in", levels, &LevelStats::rays_in);
        bars("tri tests", levels, &LevelStats::ray_triangle_tests);
        bars("box tests", levels, &LevelStats::ray_box_tests);
    }

    ImGui::Separator();
    if (ImGui::Button("compare methods")) s.compare_requested = true;
    ImGui::SameLine();
    ImGui::TextDisabled("traces one camera ray per pixel with every method");
    if (!s.comparison.empty() && ImGui::BeginTable("compare", 4, ImGuiTableFlags_Borders)) {
        for (const char* h : {"method", "ms", "box tests / ray", "tri tests / ray"})
            ImGui::TableSetupColumn(h);
        ImGui::TableHeadersRow();
        for (const MethodTotals& m : s.comparison) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(std::string(method_name(m.method)).c_str());
            ImGui::TableNextColumn();
            if (!m.error.empty()) {
                ImGui::TextUnformatted(m.error.c_str());
                continue;
            }
            const double n = double(std::max<std::uint64_t>(m.stats.rays, 1));
            ImGui::Text("%.1f", m.seconds * 1e3);
            ImGui::TableNextColumn();
            ImGui::Text("%.1f", double(m.stats.ray_box_tests) / n);
            ImGui::TableNextColumn();
            ImGui::Text("%.1f", double(m.stats.ray_triangle_tests) / n);
        }
        ImGui::EndTable();
    }
    ImGui::End();
}

}  // namespace edacrt::app
