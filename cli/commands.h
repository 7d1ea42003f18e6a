#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace edacrt::cli {

/// Each adds its subcommand to `app` and returns the function that runs it once parsed.
std::function<void()> add_render_command(CLI::App& app);
std::function<void()> add_trace_command(CLI::App& app);
std::function<void()> add_camera_rays_command(CLI::App& app);
std::function<void()> add_accuracy_command(CLI::App& app);
std::function<void()> add_bench_command(CLI::App& app);
std::function<void()> add_info_command(CLI::App& app);

}  // namespace edacrt::cli
