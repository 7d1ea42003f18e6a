#pragma once
// edacrt bench --dynamic: every method over the frames of an animation, each frame's time split
// into the update of the method's structure (rebuild, refit or none) and the trace.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace edacrt::cli {

/// The flags of `edacrt bench` that apply (copied by bench_command.cpp), and three of its own
/// (animation, rays_per_triangle, frames: the defaults here).
struct DynamicBenchOptions {
    std::vector<std::string> scenes;  // names or paths (bench_scenes.h); empty: bunny, sponza
    std::filesystem::path scenes_dir;
    bool scenes_dir_required = false;
    std::string animation = "wave";  // a spec of load_animated_scene()
    std::vector<double> rays_per_triangle = {0.0625, 0.125, 0.25, 0.5, 1,
                                             2,      4,     8,    16};  // the sweep, 1 spp
    int frames = 8;  // timed frames per set, spread over one period of the animation
    std::vector<std::string> methods;
    std::vector<int> spp;  // camera sets at width x height
    int width = 0, height = 0;
    int threads = 0;  // 0: all cores
    std::uint32_t seed = 0;
    std::string json_path, markdown_path;
};

/// Runs the benchmark; prints the table, writes the JSON and markdown asked for. Throws
/// InputError for bad options, std::runtime_error when methods disagree on a frame.
void run_dynamic_bench(const DynamicBenchOptions& options);

}  // namespace edacrt::cli
