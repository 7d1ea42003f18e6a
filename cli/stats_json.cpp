#include "stats_json.h"

#include <algorithm>

namespace edacrt::cli {

nlohmann::json to_json(const TraceDetail& detail) {
    nlohmann::json levels = nlohmann::json::array();
    for (std::size_t d = 0; d < detail.levels.size(); ++d) {
        const LevelStats& l = detail.levels[d];
        const auto mean = [&](double sum) {
            return l.alpha_children ? sum / double(l.alpha_children) : 0.0;
        };
        levels.push_back({{"level", d},
                          {"nodes", l.nodes},
                          {"leaves", l.leaves},
                          {"rays_in", l.rays_in},
                          {"rays_passed", l.rays_passed},
                          {"filters_done", l.filters_done},
                          {"filters_skipped", l.filters_skipped},
                          {"second_splits", l.second_splits},
                          {"triangles", l.triangles},
                          {"ray_box_tests", l.ray_box_tests},
                          {"sample_box_tests", l.sample_box_tests},
                          {"filter_box_tests", l.filter_box_tests},
                          {"ray_triangle_tests", l.ray_triangle_tests},
                          {"sampled_rays", l.sampled_rays},
                          {"candidate_splits", l.candidate_splits},
                          {"order_hits", l.order_hits},
                          {"order_misses", l.order_misses},
                          {"culled_by_distance", l.culled_by_distance},
                          {"alpha_children", l.alpha_children},
                          {"alpha_estimated_mean", mean(l.alpha_estimated_sum)},
                          {"alpha_true_mean", mean(l.alpha_true_sum)},
                          {"alpha_error_mean", mean(l.alpha_error_sum)},
                          {"seconds_sampling", l.phase_seconds[0]},
                          {"seconds_binning", l.phase_seconds[1]},
                          {"seconds_filtering", l.phase_seconds[2]},
                          {"seconds_leaves", l.phase_seconds[3]},
                          {"seconds", l.seconds()}});
    }
    double box_sum = 0, tri_sum = 0, miss_sum = 0;
    std::uint32_t box_max = 0, tri_max = 0, deepest = 0;
    for (const RayStats& r : detail.rays) {
        box_sum += r.ray_box_tests;
        tri_sum += r.ray_triangle_tests;
        miss_sum += r.order_misses;
        box_max = std::max(box_max, r.ray_box_tests);
        tri_max = std::max(tri_max, r.ray_triangle_tests);
        deepest = std::max<std::uint32_t>(deepest, r.deepest_level);
    }
    const double n = std::max<double>(1.0, double(detail.rays.size()));
    const RootStats& root = detail.root;
    return {{"root",
             {{"rays", root.rays},
              {"entered", root.entered},
              {"box_tests", root.box_tests},
              {"seconds", root.seconds}}},
            {"levels", levels},
            {"per_ray",
             {{"rays", detail.rays.size()},
              {"ray_box_tests_mean", box_sum / n},
              {"ray_box_tests_max", box_max},
              {"ray_triangle_tests_mean", tri_sum / n},
              {"ray_triangle_tests_max", tri_max},
              {"order_misses_mean", miss_sum / n},
              {"deepest_level_max", deepest}}}};
}

std::string json_text(const nlohmann::json& json) {
    return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace edacrt::cli
