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
