#include "script.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>

#include "util/error.h"
#include "util/input_file.h"

namespace edacrt::app {
namespace {

/// What the verb's numbers must be, for its error message.
std::string kind_text(ScriptArgs kind) {
    switch (kind) {
        case ScriptArgs::count:
            return "whole numbers from 0";
        case ScriptArgs::fraction:
            return "numbers from 0 to 1";
        case ScriptArgs::seconds:
            return "seconds, more than 0 and at most 86400";
        default:
            return "numbers";
    }
}

/// The whole word as a number of the verb's kind, or nullopt.
std::optional<double> parse_number(const std::string& word, ScriptArgs kind) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value))
        return std::nullopt;
    if (kind == ScriptArgs::count && !(value >= 0.0 && value <= 1e9 && value == std::floor(value)))
        return std::nullopt;
    if (kind == ScriptArgs::fraction && !(value >= 0.0 && value <= 1.0)) return std::nullopt;
    if (kind == ScriptArgs::seconds && !(value > 0.0 && value <= 86400.0)) return std::nullopt;
    return value;
}

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
        const ScriptVerb* verb = nullptr;
        for (const ScriptVerb& v : script_verbs())
            if (v.name == command.verb) verb = &v;
        if (!verb) fail("unknown script command '" + command.verb + "'");
        if (command.args.size() != verb->args)
            fail("'" + command.verb + "' takes " + std::to_string(verb->args) + " argument(s)");
        if (verb->kind != ScriptArgs::words)
            for (const std::string& word : command.args) {
                const auto value = parse_number(word, verb->kind);
                if (!value)
                    fail("'" + command.verb + "' takes " + kind_text(verb->kind) + ", got '" +
                         word + "'");
                command.numbers.push_back(*value);
            }
        commands.push_back(std::move(command));
    }
    return commands;
}

std::string script_help() {
    std::string help = "Script commands (--script FILE), one per line; '#' starts a comment:\n";
    for (const ScriptVerb& verb : script_verbs()) {
        std::string head = "  " + std::string(verb.name);
        if (!verb.usage.empty()) head += " " + std::string(verb.usage);
        head.resize(std::max<std::size_t>(head.size() + 1, 24), ' ');
        help += head + std::string(verb.help) + "\n";
    }
    return help;
}

std::vector<ScriptCommand> load_script(const std::string& path) {
    return parse_script(read_text_file(path, "script"), path);
}

}  // namespace edacrt::app
