#pragma once
// Runs the edacrt command-line tool from tests.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
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

/// `edacrt ARGS` running in the background (not through a shell, which would make it ignore
/// SIGINT), stdout and stderr together into `output`, for tests that signal it. Killed and
/// reaped by the destructor if still running.
class BackgroundCli {
  public:
    BackgroundCli(const std::string& args, std::filesystem::path output);
    ~BackgroundCli();
    BackgroundCli(const BackgroundCli&) = delete;
    BackgroundCli& operator=(const BackgroundCli&) = delete;

    /// Waits until the output contains `text`; false when the process ended or time ran out.
    bool wait_for_output(const std::string& text, std::chrono::seconds timeout);
    void signal(int number) const;
    /// The wait status (sys/wait.h) once it ended, or nullopt when time ran out.
    std::optional<int> wait(std::chrono::seconds timeout);
    std::string output() const;

  private:
    bool running();
    pid_t pid_ = -1;
    std::optional<int> status_;
    std::filesystem::path output_;
};

}  // namespace edacrt::test
