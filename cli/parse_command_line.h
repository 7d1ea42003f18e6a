#pragma once
// Command-line parsing as both tools (edacrt, edacrt_viewer) report it: --help and --version
// print to stdout and exit 0; a usage error prints one line "TOOL: error: WHAT" and a hint on
// stderr, and exits 2 (CLI11_PARSE would print its own two lines and exit 105 to 114).
#include <CLI/CLI.hpp>
#include <optional>

namespace edacrt::cli {

/// Adds --version ("TOOL VERSION", the CMake project's version) to `app` and parses the
/// command line; returns the exit status when the program should stop here, nullopt when it
/// should go on.
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv);

}  // namespace edacrt::cli
