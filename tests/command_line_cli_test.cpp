// How edacrt reports its command line, as other command-line tools do: --version, --help, and
// usage errors as one "edacrt: error: ..." line with exit status 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cli_runner.h"

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
}

}  // namespace
}  // namespace edacrt
