#include "script.h"

#include <sstream>

#include "util/error.h"
#include "util/input_file.h"

namespace edacrt::app {
namespace {

struct Verb {
    std::string_view name;
    std::size_t args;
};
constexpr Verb kVerbs[] = {{"set", 2},        {"view", 1},         {"wait-spp", 1},
                           {"frames", 1},     {"orbit", 2},        {"quit", 0},
                           {"screenshot", 1}, {"tab", 1},          {"panels", 1},
                           {"analysis", 1},   {"help", 1},         {"check-layout", 0},
                           {"save-view", 1},  {"save-linear", 1},  {"write-command", 1},
                           {"record", 0},     {"pick", 2},         {"wait-analysis", 0},
                           {"compare", 0},    {"wait-compare", 0}, {"wait-played", 1}};

}  // namespace

std::vector<ScriptCommand> parse_script(std::string_view text, const std::string& source) {
    std::vector<ScriptCommand> commands;
    std::istringstream in{std::string(text)};
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        ScriptCommand command;
        command.line = number;
        if (!(words >> command.verb)) continue;
        for (std::string word; words >> word;) command.args.push_back(word);
        const auto fail = [&](const std::string& what) {
            throw InputError(source + ":" + std::to_string(number) + ": " + what);
        };
        const Verb* verb = nullptr;
        for (const Verb& v : kVerbs)
            if (v.name == command.verb) verb = &v;
        if (!verb) fail("unknown script command '" + command.verb + "'");
        if (command.args.size() != verb->args)
            fail("'" + command.verb + "' takes " + std::to_string(verb->args) + " argument(s)");
        commands.push_back(std::move(command));
    }
    return commands;
}

std::vector<ScriptCommand> load_script(const std::string& path) {
    return parse_script(read_text_file(path, "script"), path);
}

}  // namespace edacrt::app
