#pragma once
// Runs the edacrt command-line tool from tests.
#include <string>

namespace edacrt::test {

struct CliResult {
    int exit_code;
    std::string output;  // stdout and stderr together
};

/// Runs `edacrt ARGS` through the shell.
CliResult run_cli(const std::string& args);

/// Runs a shell command line, stdout and stderr together.
CliResult run_command(const std::string& shell_command);

}  // namespace edacrt::test
