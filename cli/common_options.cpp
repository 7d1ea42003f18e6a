#include "common_options.h"

#include <chrono>
#include <iostream>
#include <map>
#include <optional>

#include "enum_flags.h"
#include "progress.h"
#include "scene/builtin_scenes.h"
#include "trace/stats_json.h"
#include "util/error.h"
#include "util/output_file.h"
#include "util/printable.h"

namespace edacrt::cli {

void add_common_options(CLI::App& command, CommonOptions& options) {
    command
        .add_option("--scene", options.scene,
                    "OBJ file, or a built-in scene:\n" + builtin_scene_help())
        ->required();
    flags::add_enum_option(command, "--method", options.method, kMethods, "tracing method");
    flags::add_enum_option(command, "--embree-mode", options.embree_mode, kEmbreeModes,
                           "how embree takes rays");
    command.add_option("--threads", options.threads, "worker threads (0: all cores)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    command.add_option("--stats", options.stats_path,
                       "write timings and counters to this JSON file");
    add_quiet_option(command, options.quiet);

    // EDACRT (and, where they apply, DACRT) parameters, generated from their descriptions
    // (engine/trace/edacrt_params.h): a preset first, then the flags given override it.
    const std::string group = "EDACRT parameters";
    std::string presets;
    for (std::string_view name : preset_names())
        presets += std::string(presets.empty() ? "" : "|") += name;
    command
        .add_option("--preset", options.preset,
                    "start from a parameter preset: " + presets +
                        " (paper: the paper's choices; dacrt: the DACRT baseline)")
        ->capture_default_str()
        ->check([](const std::string& name) -> std::string {
            try {
                preset_params(name);
                return {};
            } catch (const InputError& e) {
                return e.what();
            }
        })
        ->group(group);
    options.param_values.assign(edacrt_param_info().size(), {});
    for (std::size_t i = 0; i < edacrt_param_info().size(); ++i) {
        const ParamInfo& info = edacrt_param_info()[i];
        std::string help(info.help);
        if (info.kind == ParamInfo::Kind::choice) {
            help += " One of:";
            for (std::string_view name : info.choices) help += std::string(" ") += name;
            help += ".";
        }
        command.add_option("--" + std::string(info.key), options.param_values[i], help)
            ->default_str(param_text(EdacrtParams{}, info))
            ->check([&info](const std::string& text) -> std::string {
                try {
                    EdacrtParams scratch;
                    set_param(scratch, info, text);
                    return {};
                } catch (const InputError& e) {
                    return e.what();
                }
            })
            ->group(group);
    }
    command.parse_complete_callback([&options] {
        try {
            options.edacrt = preset_params(options.preset);
            for (std::size_t i = 0; i < options.param_values.size(); ++i) {
                if (options.param_values[i].empty()) continue;
                const ParamInfo& info = edacrt_param_info()[i];
                if (options.method == Method::dacrt && dacrt_sets(info.key))
                    throw InputError("--" + std::string(info.key) +
                                     " is what makes dacrt DACRT; vary it with --method edacrt "
                                     "--preset dacrt --" +
                                     std::string(info.key) + " ...");
                set_param(options.edacrt, info, options.param_values[i]);
            }
            validate(options.edacrt);
        } catch (const InputError& e) {
            throw CLI::ValidationError(e.what());
        }
    });
}

std::unique_ptr<Tracer> make_tracer(const CommonOptions& options) {
    return edacrt::make_tracer(options.method, options.edacrt, options.embree_mode);
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
        std::cerr << "edacrt: warning: " << printable(warning) << "\n";
    std::cerr << "loaded " << printable(scene.source) << ": " << scene.triangle_count()
              << " triangles, " << scene.materials.size() << " materials in "
              << seconds_since(start) << " s\n";
    return scene;
}

void write_stats(const CommonOptions& options, const nlohmann::json& stats) {
    if (options.stats_path.empty()) return;
    write_file(options.stats_path, json_text(stats), "statistics");
}

void check_outputs_spare_scene(const std::vector<NamedPath>& outputs, const Scene& scene) {
    std::vector<NamedPath> inputs;
    for (const std::string& file : scene.inputs) inputs.push_back({"scene's", file});
    check_distinct_files(outputs, inputs);
}

void check_flags(const std::function<void()>& checks) {
    try {
        checks();
    } catch (const UsageError&) {
        throw;
    } catch (const InputError& e) {
        throw UsageError(e.what());
    }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void check_writable(const std::string& path, const char* option) {
    if (path.empty()) return;
    try {
        check_output_file(path, "file");
    } catch (const InputError& e) {
        throw InputError(std::string(option) + " " + e.what());
    }
}

}  // namespace edacrt::cli
