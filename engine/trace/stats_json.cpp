#include "trace/stats_json.h"

#include <algorithm>
#include <iterator>
#include <vector>

namespace edacrt {

namespace {

/// The per-node alpha errors of a level's (or all levels') split children: quantiles, and
/// the counts per bin up to the last that is not empty.
nlohmann::json alpha_errors(const LevelStats& l) {
    const auto* bins = std::begin(l.alpha_error_bins);
    const auto* last = std::find_if(std::rbegin(l.alpha_error_bins), std::rend(l.alpha_error_bins),
                                    [](std::uint64_t n) { return n > 0; })
                           .base();
    return {{"children", l.alpha_children},
            {"mean", l.alpha_children ? l.alpha_error_sum / double(l.alpha_children) : 0.0},
            {"p50", l.alpha_error_quantile(0.5)},
            {"p90", l.alpha_error_quantile(0.9)},
            {"max", l.alpha_error_max},
            {"bin_width", kAlphaErrorBinWidth},
            {"bins", std::vector<std::uint64_t>(bins, last)}};
}

}  // namespace

nlohmann::json stats_json(const TraceDetail& detail) {
    nlohmann::json levels = nlohmann::json::array();
    for (std::size_t d = 0; d < detail.levels.size(); ++d) {
        const LevelStats& l = detail.levels[d];
        const auto mean = [&](double sum) {
            return l.alpha_children ? sum / double(l.alpha_children) : 0.0;
        };
        const double samples_per_node =
            l.sampled_nodes ? double(l.sampled_rays) / double(l.sampled_nodes) : 0.0;
        nlohmann::json sources;
        for (const auto& source : kAlphaSources)
            sources[std::string(source.name)] = l.alpha_sources[int(source.value)];
        levels.push_back({{"level", d},
                          {"nodes", l.nodes},
                          {"leaves", l.leaves},
                          {"rays_in", l.rays_in},
                          {"rays_passed", l.rays_passed},
                          {"filters_done", l.filters_done},
                          {"filters_skipped", l.filters_skipped},
                          {"second_splits", l.second_splits},
                          {"speculated", l.speculated},
                          {"triangles", l.triangles},
                          {"ray_box_tests", l.ray_box_tests},
                          {"sample_box_tests", l.sample_box_tests},
                          {"filter_box_tests", l.filter_box_tests},
                          {"ray_triangle_tests", l.ray_triangle_tests},
                          {"sampled_rays", l.sampled_rays},
                          {"sampled_nodes", l.sampled_nodes},
                          {"samples_per_node_mean", samples_per_node},
                          {"candidate_splits", l.candidate_splits},
                          {"order_hits", l.order_hits},
                          {"order_misses", l.order_misses},
                          {"culled_by_distance", l.culled_by_distance},
                          {"alpha_children", l.alpha_children},
                          {"alpha_estimated_mean", mean(l.alpha_estimated_sum)},
                          {"alpha_true_mean", mean(l.alpha_true_sum)},
                          {"alpha_error_mean", mean(l.alpha_error_sum)},
                          {"alpha_error", alpha_errors(l)},
                          {"alpha_sources", sources},
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
    LevelStats all;
    for (const LevelStats& l : detail.levels) all += l;
    return {{"root",
             {{"rays", root.rays},
              {"entered", root.entered},
              {"box_tests", root.box_tests},
              {"seconds", root.seconds}}},
            {"levels", levels},
            {"alpha_error", alpha_errors(all)},
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

}  // namespace edacrt
