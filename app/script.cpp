#include "script.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>

#include "util/error.h"
#include "util/input_file.h"

namespace edacrt::app {
namespace {

// What a verb's arguments are: words, counts (whole numbers >= 0), finite numbers, fractions
// (0 to 1) or durations (seconds, more than 0 and at most a day).
enum class Args { words, count, real, fraction, seconds };

struct Verb {
    std::string_view name;
    std::size_t args;
    Args kind = Args::words;
};
constexpr Verb kVerbs[] = {{"set", 2},
                           {"view", 1},
                           {"wait-spp", 1, Args::count},
                           {"frames", 1, Args::count},
                           {"orbit", 2, Args::real},
                           {"quit", 0},
                           {"screenshot", 1},
                           {"tab", 1},
                           {"panels", 1},
                           {"analysis", 1},
                           {"help", 1},
                           {"check-layout", 0},
                           {"save-view", 1},
                           {"save-linear", 1},
                           {"write-command", 1},
                           {"bookmark", 1},
                           {"record", 0},
                           {"pick", 2, Args::real},
                           {"wait-analysis", 0},
                           {"compare", 0},
                           {"wait-compare", 0},
                           {"wait-played", 1, Args::count},
                           {"wait-loaded", 0},
                           {"wait-error", 0},
                           {"wait-settled", 0},
                           {"timeout", 1, Args::seconds},
                           {"layout", 1},
                           {"pick-image", 2, Args::fraction}};

/// What the verb's numbers must be, for its error message.
std::string kind_text(Args kind) {
    switch (kind) {
        case Args::count:
            return "whole numbers from 0";
        case Args::fraction:
            return "numbers from 0 to 1";
        case Args::seconds:
            return "seconds, more than 0 and at most 86400";
        default:
            return "numbers";
    }
}

/// The whole word as a number of the verb's kind, or nullopt.
std::optional<double> parse_number(const std::string& word, Args kind) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value))
        return std::nullopt;
    if (kind == Args::count && !(value >= 0.0 && value <= 1e9 && value == std::floor(value)))
        return std::nullopt;
    if (kind == Args::fraction && !(value >= 0.0 && value <= 1.0)) return std::nullopt;
    if (kind == Args::seconds && !(value > 0.0 && value <= 86400.0)) return std::nullopt;
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
        const Verb* verb = nullptr;
        for (const Verb& v : kVerbs)
            if (v.name == command.verb) verb = &v;
        if (!verb) fail("unknown script command '" + command.verb + "'");
        if (command.args.size() != verb->args)
            fail("'" + command.verb + "' takes " + std::to_string(verb->args) + " argument(s)");
        if (verb->kind != Args::words)
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

std::vector<ScriptCommand> load_script(const std::string& path) {
    return parse_script(read_text_file(path, "script"), path);
}

}  // namespace edacrt::app
