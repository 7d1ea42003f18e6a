#include "parse_command_line.h"

#include <algorithm>
#include <iostream>
#include <string>

#include "util/error.h"
#include "util/printable.h"

namespace edacrt::flags {

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
        // The command that failed: the deepest one parsed, for the hint.
        std::string command = app.get_name();
        for (const CLI::App* at = &app; !at->get_subcommands().empty();) {
            at = at->get_subcommands().front();
            command += " " + at->get_name();
        }
        std::string what = e.what();
        if (command == app.get_name() && argc > 1 && argv[1][0] != '-' &&
            app.get_subcommands().empty() &&
            !app.get_subcommands([](CLI::App*) { return true; }).empty())
            what = "unknown command '" + std::string(argv[1]) + "'";
        std::replace(what.begin(), what.end(), '\n', ' ');
        std::cerr << app.get_name() << ": error: " << what << "\nrun '" << command
                  << " --help' for the options\n";
        return kExitUsageError;
    } catch (const InputError& e) {
        std::cerr << app.get_name() << ": error: " << printable(e.what()) << "\n";
        return kExitInputError;
    }
}

int run_reporting_errors(const std::string& tool, const std::function<int()>& work) {
    try {
        return work();
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
