#pragma once
// Command-line parsing and errors as both tools (edacrt, edacrt_viewer) report them: --help
// and --version print to stdout and exit 0; a usage error prints one line "TOOL: error: WHAT"
// and a hint on stderr, and exits 2 (CLI11_PARSE would print its own two lines and exit 105 to
// 114); bad input exits 1 (also a flag's value refused while parsing, such as an unknown name of
// an enum flag), a bug 70.
#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>

namespace edacrt::flags {

// Exit statuses (listed in --help): 0 success, and 130 for Ctrl-C (cli/interrupt.h).
constexpr int kExitInputError = 1;      // a file or value that is wrong, or cannot be written
constexpr int kExitUsageError = 2;      // a command line that cannot be parsed
constexpr int kExitInternalError = 70;  // sysexits' EX_SOFTWARE: a bug, not the user's input

/// Adds --version ("TOOL VERSION", the CMake project's version) to `app` and parses the
/// command line; returns the exit status when the program should stop here, nullopt when it
/// should go on. An InputError thrown by a flag's callback is reported as run_reporting_errors()
/// reports it.
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv);

/// Runs `work` and returns its exit status, or reports what it threw on stderr, escaped:
/// "TOOL: error: WHAT" for an InputError or out of memory (kExitInputError), "TOOL: internal
/// error: WHAT" for any other exception (kExitInternalError).
int run_reporting_errors(const std::string& tool, const std::function<int()>& work);

}  // namespace edacrt::flags
