// Progress of long commands: redrawn in place on a terminal (a pseudo-terminal here), one plain
// line per step on a pipe, nothing with --quiet; results stay on stdout.
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "cli_runner.h"
#include "test_paths.h"

extern char** environ;

namespace edacrt {
namespace {

class ProgressCli : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("edacrt_progress_cli_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::filesystem::path dir_;
};

struct TerminalRun {
    int exit_code = -1;
    std::string output;  // what the terminal received, stdout and stderr together
};

/// Runs edacrt on a pseudo-terminal of `columns` columns, with TERM set as a terminal's is.
TerminalRun run_on_terminal(const std::vector<std::string>& args, int columns) {
    // Everything the child needs is built before the fork: only exec runs after it.
    std::vector<std::string> strings = {test::cli_path().string()};
    strings.insert(strings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& s : strings) argv.push_back(s.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_strings = {"TERM=xterm"};
    for (char** e = environ; *e; ++e)
        if (std::string_view(*e).substr(0, 5) != "TERM=") env_strings.emplace_back(*e);
    std::vector<char*> envp;
    for (std::string& s : env_strings) envp.push_back(s.data());
    envp.push_back(nullptr);

    winsize size{};
    size.ws_col = static_cast<unsigned short>(columns);
    size.ws_row = 40;
    int master = -1;
    const pid_t pid = forkpty(&master, nullptr, nullptr, &size);
    if (pid < 0) return {-1, "forkpty failed"};
    if (pid == 0) {
        execve(argv[0], argv.data(), envp.data());
        _exit(127);
    }
    TerminalRun run;
    char buffer[4096];
    for (;;) {
        const ssize_t n = read(master, buffer, sizeof buffer);
        if (n > 0)
            run.output.append(buffer, std::size_t(n));
        else if (n < 0 && errno == EINTR)
            continue;
        else
            break;  // EIO once the child has closed the terminal
    }
    int status = 0;
    waitpid(pid, &status, 0);
    close(master);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++n;
    return n;
}

const std::string kRender =
    "render --scene builtin:cornell --width 32 --height 24 --spp 8 --samples-per-pass 2 ";

TEST_F(ProgressCli, OnATerminalOneLineIsRedrawnInPlace) {
    const TerminalRun run =
        run_on_terminal({"render", "--scene", "builtin:cornell", "--width", "32", "--height", "24",
                         "--spp", "8", "--samples-per-pass", "2", "--out", path("t.png")},
                        72);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    // Drawn from the line's start and cleared to its end, with the bar, the fraction, the
    // rate and the time: never a line per step.
    EXPECT_NE(run.output.find("\rrender [##########] 100%  8/8 spp  "), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find("\rrender [##--------]  25%  2/8 spp  "), std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find(" elapsed"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(" spp/s"), std::string::npos) << run.output;
    EXPECT_EQ(count(run.output, "render: "), 0u) << run.output;
    // The line is erased before the result is written on stdout.
    EXPECT_NE(run.output.find("\r\033[Krendered 32x24 at 8 spp"), std::string::npos) << run.output;
    // No drawn line is wider than the terminal, or it would wrap and not redraw in place.
    std::string piece;
    std::istringstream pieces(run.output);
    while (std::getline(pieces, piece, '\r')) {
        const std::size_t end = piece.find("\033[K");
        EXPECT_LT(piece.substr(0, end).size(), 72u) << piece;
    }
}

TEST_F(ProgressCli, OnAPipeEachStepIsOnePlainLine) {
    const auto result = test::run_cli(kRender + "--out " + path("p.png"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(result.output.find('\033'), std::string::npos) << "no escape codes on a pipe";
    EXPECT_EQ(result.output.find('\r'), std::string::npos) << "no carriage returns on a pipe";
    EXPECT_EQ(count(result.output, "\nrender: "), 4u) << result.output;
    for (const char* step : {"\nrender: 2/8 spp (25.0%, ", "\nrender: 4/8 spp (50.0%, ",
                             "\nrender: 6/8 spp (75.0%, ", "\nrender: 8/8 spp (100.0%, "})
        EXPECT_NE(result.output.find(step), std::string::npos) << step << "\n" << result.output;
    EXPECT_NE(result.output.find(" spp/s, "), std::string::npos) << result.output;
    EXPECT_NE(result.output.find(" Mrays/s, "), std::string::npos) << result.output;
    EXPECT_NE(result.output.find(" elapsed, about "), std::string::npos) << result.output;

    // Progress is on stderr: stdout alone has the result and no progress.
    const auto out = test::run_command("('" + test::cli_path().string() + "' " + kRender +
                                       "--out " + path("p.png") + " 2>/dev/null)");
    ASSERT_EQ(out.exit_code, 0) << out.output;
    EXPECT_EQ(out.output.find("render: "), std::string::npos) << out.output;
    EXPECT_NE(out.output.find("rendered 32x24 at 8 spp"), std::string::npos) << out.output;

    const auto quiet = test::run_cli(kRender + "--quiet --out " + path("q.png"));
    ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
    EXPECT_EQ(quiet.output.find("render: "), std::string::npos) << quiet.output;
    EXPECT_NE(quiet.output.find("rendered 32x24 at 8 spp"), std::string::npos) << quiet.output;
}

TEST_F(ProgressCli, TraceAndBenchReportTheirSteps) {
    ASSERT_EQ(test::run_cli("camera-rays --scene builtin:cornell --width 16 --height 16 --out " +
                            path("r.bin"))
                  .exit_code,
              0);
    const auto trace = test::run_cli("trace --scene builtin:cornell --rays " + path("r.bin") +
                                     " --out " + path("h.bin"));
    ASSERT_EQ(trace.exit_code, 0) << trace.output;
    EXPECT_NE(trace.output.find("\ntrace: prepared edacrt ("), std::string::npos) << trace.output;
    EXPECT_NE(trace.output.find("\ntrace: traced 256 rays (100.0%, "), std::string::npos)
        << trace.output;
    EXPECT_EQ(trace.output.find('\033'), std::string::npos) << trace.output;

    const auto bench = test::run_cli(
        "bench --scene builtin:cube:n=2 --width 16 --height 16 "
        "--sets camera --spp 1 --repeat 1 --methods edacrt,bvh");
    ASSERT_EQ(bench.exit_code, 0) << bench.output;
    EXPECT_NE(bench.output.find(" camera-1spp, 256 rays, "), std::string::npos) << bench.output;
    EXPECT_NE(bench.output.find(" (100.0%, "), std::string::npos) << bench.output;
    EXPECT_EQ(bench.output.find('\033'), std::string::npos) << bench.output;
}

TEST_F(ProgressCli, AccuracyShowsEachPhaseAndCanSkipNaive) {
    const std::string accuracy =
        "accuracy --scene builtin:cornell --rays 100 --repeats 1 --stats " + path("a.json") + " ";
    const auto all = test::run_cli(accuracy + "--methods naive,edacrt");
    ASSERT_EQ(all.exit_code, 0) << all.output;
    for (const char* step :
         {"\nreference: camera done (", "\nreference: axis-parallel done (100.0%",
          "\nnaive: camera, run 1/1 done (", "\nnaive: axis-parallel, run 1/1 done (100.0%",
          "\nedacrt: axis-parallel, run 1/1 done (100.0%", "\nnaive   camera  "})
        EXPECT_NE(all.output.find(step), std::string::npos) << step << "\n" << all.output;
    EXPECT_EQ(all.output.find('\033'), std::string::npos) << all.output;

    const auto skipped = test::run_cli(accuracy + "--methods naive,edacrt --skip-naive");
    ASSERT_EQ(skipped.exit_code, 0) << skipped.output;
    EXPECT_EQ(skipped.output.find("naive"), std::string::npos) << skipped.output;
    EXPECT_NE(skipped.output.find("\nedacrt  camera  "), std::string::npos) << skipped.output;
    const auto stats = nlohmann::json::parse(std::ifstream(path("a.json")));
    EXPECT_TRUE(stats["skipped_naive"].get<bool>());
    EXPECT_EQ(stats["results"].size(), 5u) << "edacrt on the five ray sets";

    const auto nothing = test::run_cli(accuracy + "--methods naive --skip-naive");
    EXPECT_EQ(nothing.exit_code, 2) << nothing.output;  // a usage error
    EXPECT_NE(nothing.output.find("no method left to measure"), std::string::npos)
        << nothing.output;
}

}  // namespace
}  // namespace edacrt
