#include "parse_command_line.h"

#include <algorithm>
#include <charconv>
#include <iostream>
#include <string>

#include "util/error.h"
#include "util/printable.h"

namespace edacrt::flags {
namespace {

/// Prints the error and a hint naming the command that failed (the deepest one parsed).
int usage_error(const CLI::App& app, const std::string& what) {
    std::string command = app.get_name();
    for (const CLI::App* at = &app; !at->get_subcommands().empty();) {
        at = at->get_subcommands().front();
        command += " " + at->get_name();
    }
    std::cerr << app.get_name() << ": error: " << what << "\nrun '" << command
              << " --help' for the options\n";
    return kExitUsageError;
}

}  // namespace

std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
    app.set_version_flag("--version", app.get_name() + " " + EDACRT_VERSION);
    app.footer(
        "Exit status: 0 success, 1 bad input or a file that cannot be read or written, 2 usage "
        "error, 70 internal error (a bug), 130 interrupted (Ctrl-C).");
    try {
        app.parse(argc, argv);
        return std::nullopt;
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::string what = e.what();
        if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty() &&
            !app.get_subcommands([](CLI::App*) { return true; }).empty())
            what = "unknown command '" + std::string(argv[1]) + "'";
        std::replace(what.begin(), what.end(), '\n', ' ');
        return usage_error(app, what);
    } catch (const InputError& e) {  // a flag's value refused by its callback
        return usage_error(app, printable(e.what()));
    }
}

CLI::Validator whole_number(std::uint64_t max) {
    return CLI::Validator(
        [max](std::string& text) -> std::string {
            std::uint64_t value = 0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
            if (ec == std::errc() && end == text.data() + text.size() && value <= max) return {};
            return "expected a whole number from 0 to " + std::to_string(max) + ", got " +
                   printable(text);
        },
        "UINT");
}

int run_reporting_errors(const std::string& tool, const std::function<int()>& work) {
    try {
        return work();
    } catch (const UsageError& e) {
        std::cerr << tool << ": error: " << printable(e.what()) << "\n";
        return kExitUsageError;
    } catch (const InputError& e) {
        // Messages quote names from files: escaped, as everything printed from a file is.
        std::cerr << tool << ": error: " << printable(e.what()) << "\n";
    } catch (const std::bad_alloc&) {
        std::cerr << tool << ": error: out of memory\n";
    } catch (const std::exception& e) {
        std::cerr << tool << ": internal error: " << printable(e.what()) << "\n";
        return kExitInternalError;
    }
    return kExitInputError;
}

}  // namespace edacrt::flags
