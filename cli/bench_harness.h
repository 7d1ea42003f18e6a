#pragma once
// edacrt bench: every method on the same rays in one process, frame by frame, methods
// interleaved, and a check that all of them found the same hits. Still frames (the default)
// keep nothing between frames: a new tracer, set_scene() and trace(). Animated frames
// (--dynamic) follow an animation with each tracer kept, update_scene() (rebuild, refit or
// none) and trace(), on camera rays and a sweep of rays per triangle. One loop takes both.
#include <cstdint>
#include <string>
#include <vector>

#include "bench_rays.h"

namespace edacrt::cli {

struct BenchOptions {
    std::string scenes_dir;           // empty: default_scenes_dir()
    std::vector<std::string> scenes;  // names or paths (bench_scenes.h); empty: the manifest's
                                      // list "bench", or "bench_dynamic" with --dynamic
    std::vector<std::string> sets = enum_name_list(kRaySetKinds);  // still only
    std::vector<int> spp = {1, 4, 16};
    std::vector<std::string> methods = {"edacrt", "dacrt", "bvh", "embree"};
    int width = 1024, height = 1024;
    int repeat = 5;   // still frames per method and set
    int threads = 0;  // 0: all cores
    bool thread_sweep = false;
    bool quiet = false;
    std::uint32_t seed = 1;
    std::string json_path, markdown_path;
    std::string rays_dir;  // --write-rays (still only)
    // --dynamic: the frames of an animation instead of still frames.
    bool dynamic = false;
    std::string animation = "wave";  // a spec of load_animated_scene()
    std::vector<double> rays_per_triangle = {0.0625, 0.125, 0.25, 0.5, 1,
                                             2,      4,     8,    16};  // the sweep, 1 spp
    int frames = 8;  // timed frames per set, spread over one period of the animation
};

/// Runs the benchmark; prints the table, writes the JSON and markdown asked for. Throws
/// InputError for bad options, std::runtime_error when methods disagree.
void run_bench(const BenchOptions& options);

}  // namespace edacrt::cli
