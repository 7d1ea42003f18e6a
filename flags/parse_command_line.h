#pragma once
// Command-line parsing and errors as both tools (edacrt, edacrt_viewer) report them: --help
// and --version print to stdout and exit 0; a usage error prints one line "TOOL: error: WHAT"
// and a hint on stderr, and exits 2 (CLI11_PARSE would print its own two lines and exit 105 to
// 114), as does a flag's value refused while parsing (an unknown name of an enum flag) or a
// UsageError thrown later (a value out of range, flags that do not go together); bad input (a
// file's content, a file that cannot be read or written) exits 1, a bug 70.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace edacrt::flags {

// Exit statuses (listed in --help): 0 success, and 130 for Ctrl-C (cli/interrupt.h).
constexpr int kExitInputError = 1;      // a file that is wrong, or cannot be read or written
constexpr int kExitUsageError = 2;      // a command line that cannot be parsed or is refused
constexpr int kExitInternalError = 70;  // sysexits' EX_SOFTWARE: a bug, not the user's input

/// Adds --version ("TOOL VERSION", the CMake project's version) to `app` and parses the
/// command line; returns the exit status when the program should stop here, nullopt when it
/// should go on. An InputError thrown by a flag's callback is a usage error.
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv);

/// Checks the text of an unsigned flag (a std::size_t): a whole number from 0 to `max`. CLI11
/// alone reads "-5" as 2^64 - 5 and an overflowing number as the largest one, silently.
CLI::Validator whole_number(std::uint64_t max = UINT64_MAX);

/// Runs `work` and returns its exit status, or reports what it threw on stderr, escaped:
/// "TOOL: error: WHAT" for a UsageError (kExitUsageError), an InputError or out of memory
/// (kExitInputError), "TOOL: internal error: WHAT" for any other exception (kExitInternalError).
int run_reporting_errors(const std::string& tool, const std::function<int()>& work);

}  // namespace edacrt::flags
