#pragma once
// The viewer's --script: UI actions, one per line, for headless tests and demos. Every verb is
// described once, in script_verbs() (app/script_runner.cpp): its arguments, the help that
// `edacrt_viewer --script-help` prints (script_help()), and what it does. `set KEY VALUE` takes the
// settings of app/settings_table.h and the EDACRT flags without "--". '#' starts a comment. Errors
// name the line: a bad number or `set` value, a save or write that fails, a render that fails while
// a wait-* waits for it, a wait that times out.
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace edacrt::app {

struct ScriptCommand {
    std::string verb;
    std::vector<std::string> args;
    std::vector<double> numbers;  // the arguments of verbs that take numbers, checked
    int line = 0;
};

// What a verb's arguments are: words, counts (whole numbers >= 0), finite numbers, fractions (0 to
// 1) or durations (seconds, more than 0 and at most a day).
enum class ScriptArgs { words, count, real, fraction, seconds };

class ScriptRunner;
struct ScriptStep;

/// How a script goes on after a verb's step: to the next command in this frame, to the next command
/// in the next frame (the change must be drawn or submitted first), or (a wait whose condition does
/// not hold yet) to the same command in the next frame.
enum class ScriptNext { go_on, next_frame, again };

struct ScriptVerb {
    std::string_view name;
    std::size_t args = 0;
    ScriptArgs kind = ScriptArgs::words;
    std::string_view usage;  // the arguments, as the help writes them ("N", "X Y")
    std::string_view help;   // what it does
    ScriptNext (*run)(ScriptRunner&, ScriptStep&) = nullptr;
};

/// Every verb, in the order the help lists them.
std::span<const ScriptVerb> script_verbs();

/// One line per verb: "  NAME ARGS   HELP" (wrapped), for --script-help.
std::string script_help();

/// Throws InputError ("FILE:LINE: ...") for unknown verbs, wrong argument counts or numbers (naming
/// the value).
std::vector<ScriptCommand> parse_script(std::string_view text, const std::string& source);

/// Reads and parses a script file.
std::vector<ScriptCommand> load_script(const std::string& path);

}  // namespace edacrt::app
