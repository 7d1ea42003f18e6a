#pragma once
// Options that several edacrt subcommands share, and their effects.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "trace/edacrt_params.h"
#include "trace/tracer.h"
#include "util/output_file.h"

namespace edacrt::cli {

struct CommonOptions {
    std::string scene;
    Method method = Method::edacrt;
    EmbreeMode embree_mode = kDefaultEmbreeMode;
    int threads = 0;  // 0: all hardware threads
    std::string stats_path;
    bool quiet = false;  // no progress output
    std::string preset = "default";
    std::vector<std::string> param_values;  // as given, per edacrt_param_info(); empty: not given
    EdacrtParams edacrt;                    // the preset with the given values applied
};

void add_common_options(CLI::App& command, CommonOptions& options);

/// The tracer --method names, with its parameters; throws InputError for bad ones.
std::unique_ptr<Tracer> make_tracer(const CommonOptions& options);

/// Limits oneTBB to --threads for as long as the returned object lives.
std::unique_ptr<tbb::global_control> apply_thread_limit(const CommonOptions& options);

/// Loads the scene, printing its size and any loader warnings to stderr.
Scene load_scene_verbose(const std::string& spec);

/// Writes `stats` as pretty JSON when --stats was given.
void write_stats(const CommonOptions& options, const nlohmann::json& stats);

/// Throws InputError when `path` (given by `option`) cannot be written, so that a long run
/// fails now rather than at its end. Empty: nothing to check.
void check_writable(const std::string& path, const char* option);

// NamedPath and check_distinct_files(): util/output_file.h (the viewer checks its outputs too).

/// The same for the files a scene's loading read besides those on the command line (its MTL
/// libraries, the meshes of an animation file, key frames: Scene::inputs), once it is loaded
/// and before anything is rendered or written.
void check_outputs_spare_scene(const std::vector<NamedPath>& outputs, const Scene& scene);

/// Runs the checks of flag values and combinations: an InputError they throw becomes a
/// UsageError (exit status 2), as the engine's validators (validate(RenderSettings), ...)
/// serve files and flags alike.
void check_flags(const std::function<void()>& checks);

/// Seconds since `start` on the steady clock.
double seconds_since(std::chrono::steady_clock::time_point start);

}  // namespace edacrt::cli
