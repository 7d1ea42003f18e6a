#include "common_options.h"

#include <chrono>
#include <iostream>

#include "scene/builtin_scenes.h"
#include "util/output_file.h"

namespace edacrt::cli {

void add_common_options(CLI::App& command, CommonOptions& options) {
    command
        .add_option("--scene", options.scene,
                    "OBJ file, or a built-in scene:\n" + builtin_scene_help())
        ->required();
    std::string methods;
    for (const std::string& name : method_names()) methods += (methods.empty() ? "" : "|") + name;
    command.add_option("--method", options.method, "tracing method: " + methods)
        ->capture_default_str();
    command
        .add_option("--embree-mode", options.embree_mode,
                    "how embree takes rays: single|packet8|stream")
        ->capture_default_str();
    command.add_option("--threads", options.threads, "worker threads (0: all cores)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    command.add_option("--stats", options.stats_path,
                       "write timings and counters to this JSON file");

    // EDACRT (and, where they apply, DACRT) parameters; see engine/trace/edacrt_params.h.
    EdacrtParams& p = options.edacrt;
    const auto param = [&](const char* name, auto& value, const char* what) {
        command.add_option(name, value, what)->capture_default_str()->group("EDACRT parameters");
    };
    param("--bins", p.bins, "K, bins per split (K-1 candidate splits)");
    param("--sample-threshold", p.sample_threshold, "nodes with more rays sample them");
    param("--sample-count", p.sample_count, "rays sampled per node");
    param("--leaf-rays", p.leaf_rays, "brute force when rays <= this");
    param("--leaf-tris", p.leaf_tris, "brute force when triangles <= this");
    param("--cost-leaf-max-tris", p.cost_leaf_max_tris,
          "the cost test may make leaves only this small");
    param("--c-t", p.cost_traversal, "C_T, cost of a split per ray");
    param("--c-i", p.cost_intersect, "C_I, cost of a ray-triangle test");
    param("--c-bv", p.cost_filter, "C_bv, cost of filtering a ray");
    param("--c-child", p.cost_child, "C_child, per-triangle cost of an unfiltered ray");
    param("--filter-skip", p.filter_skip, "skip filtering when most rays hit the child (0/1)");
    param("--sampling", p.sampling, "estimate hit ratios by ray sampling (0/1)");
    param("--sampling-seed", p.seed, "seed of the per-node ray sampling");
}

std::unique_ptr<Tracer> make_tracer(const CommonOptions& options) {
    return edacrt::make_tracer(parse_method(options.method), options.edacrt,
                               parse_embree_mode(options.embree_mode));
}

std::unique_ptr<tbb::global_control> apply_thread_limit(const CommonOptions& options) {
    if (options.threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 std::size_t(options.threads));
}

Scene load_scene_verbose(const std::string& spec) {
    const auto start = std::chrono::steady_clock::now();
    Scene scene = load_scene(spec);
    for (const std::string& warning : scene.warnings)
        std::cerr << "edacrt: warning: " << warning << "\n";
    std::cerr << "loaded " << scene.source << ": " << scene.triangle_count() << " triangles, "
              << scene.materials.size() << " materials in " << seconds_since(start) << " s\n";
    return scene;
}

void write_stats(const CommonOptions& options, const nlohmann::json& stats) {
    if (options.stats_path.empty()) return;
    write_file(options.stats_path, stats.dump(2) + "\n", "statistics");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace edacrt::cli
