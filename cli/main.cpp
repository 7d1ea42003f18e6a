// edacrt: the headless command-line tool. Renders images and traces ray files with any method.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "interrupt.h"
#include "parse_command_line.h"
#include "util/printable.h"

int main(int argc, char** argv) {
    // Past `ulimit -f` a write then fails with EFBIG, which OutputFile reports (the old file
    // kept, the temporary removed), instead of SIGXFSZ killing the process without a word.
    std::signal(SIGXFSZ, SIG_IGN);
    CLI::App app{
        "EDACRT Studio command-line tool: divide-and-conquer ray tracing without a stored "
        "acceleration structure.\nRun 'edacrt COMMAND --help' for the options of a command.",
        "edacrt"};
    app.require_subcommand(1);
    const auto run_render = edacrt::cli::add_render_command(app);
    const auto run_trace = edacrt::cli::add_trace_command(app);
    const auto run_camera_rays = edacrt::cli::add_camera_rays_command(app);
    const auto run_accuracy = edacrt::cli::add_accuracy_command(app);
    const auto run_bench = edacrt::cli::add_bench_command(app);
    const auto run_info = edacrt::cli::add_info_command(app);
    if (const auto status = edacrt::flags::parse_command_line(app, argc, argv)) return *status;

    const int status = edacrt::flags::run_reporting_errors("edacrt", [&] {
        try {
            if (app.got_subcommand("render")) run_render();
            if (app.got_subcommand("trace")) run_trace();
            if (app.got_subcommand("camera-rays")) run_camera_rays();
            if (app.got_subcommand("accuracy")) run_accuracy();
            if (app.got_subcommand("bench")) run_bench();
            if (app.got_subcommand("info")) run_info();
        } catch (const edacrt::cli::Interrupted& e) {
            std::fflush(stdout);  // the report of what was written comes first
            std::cerr << "edacrt: interrupted: " << edacrt::printable(e.what()) << "\n";
            return edacrt::cli::kInterruptedStatus;
        }
        return 0;
    });
    if (status != 0) return status;
    // The report on stdout is output too: a full disk or closed pipe must not pass as success.
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
        std::cerr << "edacrt: error: cannot write to standard output\n";
        return edacrt::flags::kExitInputError;
    }
    return 0;
}
