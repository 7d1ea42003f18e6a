#include "cli_runner.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>

#include "test_paths.h"

namespace edacrt::test {

CliResult run_cli(const std::string& args) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string command = "'";
    command.append(cli_path().string()).append("' ").append(args);
    return run_command(command);
}

CliResult run_command(const std::string& shell_command) {
    const std::string command = shell_command + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return {-1, "popen failed"};
    std::string output;
    std::array<char, 4096> buffer;
    while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe))
        output.append(buffer.data(), n);
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace edacrt::test
