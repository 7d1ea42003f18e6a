// How edacrt reports its command line, as other command-line tools do: --version, --help, and
// usage errors as one "edacrt: error: ..." line with exit status 2; errors while running with
// their own statuses (1 bad input, 70 a bug).
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <string>

#include "cli_runner.h"
#include "parse_command_line.h"
#include "util/error.h"

namespace edacrt {
namespace {

TEST(CommandLineCli, VersionPrintsTheProjectVersion) {
    const auto result = test::run_cli("--version");
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(result.output, "edacrt 0.1\n");
}

TEST(CommandLineCli, UsageErrorsAreOneLineWithStatus2) {
    const struct {
        std::string args, message;
    } cases[] = {
        {"", "edacrt: error: A subcommand is required\nrun 'edacrt --help'"},
        {"frobnicate", "edacrt: error: unknown command 'frobnicate'\nrun 'edacrt --help'"},
        {"render --spp abc", "edacrt: error: --spp: "},
        {"render --scene builtin:cornell --bogus",
         "edacrt: error: The following argument was "
         "not expected: --bogus\nrun 'edacrt render "
         "--help'"},
        {"trace --rays r.bin", "edacrt: error: --scene is required\nrun 'edacrt trace --help'"},
        {"render --scene builtin:cornell --bins 1",
         "edacrt: error: --bins: EDACRT parameter bins: '1' is outside"},
        {"info", "edacrt: error: scene is required"},
    };
    for (const auto& c : cases) {
        const auto result = test::run_cli(c.args);
        EXPECT_EQ(result.exit_code, 2) << c.args << "\n" << result.output;
        EXPECT_EQ(result.output.rfind(c.message, 0), 0u) << c.args << "\n" << result.output;
        // The error and the hint: two lines, no help text.
        EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 2) << c.args << "\n"
                                                                                   << result.output;
    }
    const auto help = test::run_cli("render --help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.output.find("--spp"), std::string::npos) << help.output;
    const auto statuses = test::run_cli("--help");
    EXPECT_NE(statuses.output.find("Exit status: 0 success, 1 bad input"), std::string::npos)
        << statuses.output;
    EXPECT_NE(statuses.output.find("70 internal error"), std::string::npos) << statuses.output;
}

// A flag's value out of range or flags that do not go together are usage errors too, whether
// CLI11 or the command's own checks refuse them (they once exited 1, as bad input does), and
// refused before any work; unsigned flags refuse a sign and overflow (CLI11 wraps them).
TEST(CommandLineCli, BadFlagValuesAreUsageErrors) {
    const std::string render = "render --scene builtin:sphere --width 8 --height 8 --spp 1 -q ";
    const struct {
        std::string args, message;
    } cases[] = {
        {render + "--out q.png --exposure nan", "exposure must be a finite number"},
        {render + "--out q.png --samples-per-pass -1",
         "--samples-per-pass must be 0..1024 (0: about 1M paths per pass), got -1"},
        {render + "--out q.png --samples-per-pass 1025", "--samples-per-pass must be 0..1024"},
        {render + "--out q.png --max-depth -5", "max depth must be 0..1024, got -5"},
        {render + "--out q.png --integrator ao --ao-samples 0", "ao samples must be 1..1024"},
        {render + "--out q.png --sky -1,0,0", "sky radiance must be finite and >= 0"},
        {render + "--out q.png --time-budget -1", "--time-budget must be a finite number"},
        {render + "--out q.png --method foo", "--method: unknown method 'foo'"},
        {render + "--out q.png --integrator foo", "--integrator: unknown integrator 'foo'"},
        {render + "--out q.png --tone-map foo", "--tone-map: unknown tone map 'foo'"},
        {render + "--out q.tiff", "unknown image format '.tiff'"},
        {render + "--animate twist --out 'q_%04d.png' --frames 0-2", "--frames 0-2: expected A:B"},
        {render + "--animate twist --out 'q_%04d.png' --frames 0:2 --fps 0",
         "--fps must be a number"},
        {render + "--out 'q_%04d.png' --frames 0:2", "--frames is for an animation"},
        {render + "--out q.png --time 1", "--time is for an animation"},
        {render + "--out q.png --shutter 0.5", "--shutter is for an animation"},
        {render + "--out q.png --wavefront-paths -5",
         "--wavefront-paths: expected a whole number from 0 to 18446744073709551615, got -5"},
        {render + "--out q.png --wavefront-paths 99999999999999999999",
         "--wavefront-paths: expected a whole number"},
        {render + "--out q.png --seed -1", "--seed"},
        {"render --width 8 --height 8 --out q.png", "no scene: give --scene"},
        {"info builtin:sphere --samples-per-pass -2", "--samples-per-pass must be 0..1024"},
        {"accuracy --scene builtin:sphere --rays 0", "--rays must be 1..10000000"},
        {"bench --scene builtin:sphere --sets nowhere", "unknown ray set"},
    };
    for (const auto& c : cases) {
        const auto result = test::run_cli(c.args);
        EXPECT_EQ(result.exit_code, 2) << c.args << "\n" << result.output;
        EXPECT_EQ(result.output.rfind("edacrt: error: ", 0), 0u) << c.args << "\n" << result.output;
        EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n"
                                                                    << result.output;
        EXPECT_EQ(result.output.find("loaded"), std::string::npos) << "work before the refusal";
    }
    // A file's content stays bad input.
    const auto missing = test::run_cli(render + "--out q.png --reference /nonexistent.pfm");
    EXPECT_EQ(missing.exit_code, 1) << missing.output;
}

// Both tools run their work through run_reporting_errors: a bug (an unexpected exception) is
// told apart from bad input and from a usage error by its status.
TEST(CommandLineCli, InternalErrorsHaveStatus70) {
    const auto run = [](const std::function<int()>& work) {
        testing::internal::CaptureStderr();
        const int status = flags::run_reporting_errors("tool", work);
        return std::pair(status, testing::internal::GetCapturedStderr());
    };
    EXPECT_EQ(run([] { return 0; }), std::pair(0, std::string()));
    EXPECT_EQ(run([]() -> int { throw InputError("a.obj:3: bad \x1b[31m"); }),
              std::pair(1, std::string("tool: error: a.obj:3: bad \\x1B[31m\n")));
    EXPECT_EQ(run([]() -> int { throw std::bad_alloc(); }),
              std::pair(1, std::string("tool: error: out of memory\n")));
    EXPECT_EQ(run([]() -> int { throw std::logic_error("vector::_M_range_check"); }),
              std::pair(70, std::string("tool: internal error: vector::_M_range_check\n")));
}

}  // namespace
}  // namespace edacrt
