#include "common_options.h"

#include <chrono>
#include <fstream>
#include <iostream>

#include "scene/builtin_scenes.h"
#include "util/error.h"

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
    command.add_option("--threads", options.threads, "worker threads (0: all cores)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    command.add_option("--stats", options.stats_path,
                       "write timings and counters to this JSON file");
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
    std::ofstream out(options.stats_path);
    out << stats.dump(2) << "\n";
    if (!out) throw InputError(options.stats_path + ": cannot write statistics");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace edacrt::cli
