#pragma once
// The viewer's render, display and playback settings, each described once (SettingInfo), as the
// EDACRT parameters are (engine/trace/edacrt_params.h): the viewer's command-line flags
// (--KEY), the widgets and their tooltips, the script's `set KEY VALUE` and the range checks
// all come from viewer_settings(), so a range cannot differ between them.
#include <functional>
#include <map>
#include <span>
#include <string>
#include <string_view>

namespace edacrt::app {

struct ViewerState;

/// One name of a choice (an enum's value, or one of a few numbers) and its description.
struct ChoiceEntry {
    int value;
    std::string_view name;  // as `set` and the flag take it
    std::string_view help;  // the combo's tooltip, or (steps) the widget's label
};

struct SettingInfo {
    enum class Kind {
        integer,  // a whole number in [min, max]
        real,     // a finite number in [min, max]
        choice,   // one of `choices` by name (an enum's table)
        steps,    // one of the numbers `choices` lists
        toggle,   // 0 or 1 (any non-zero number is 1); on the command line, --KEY alone is 1
    };
    std::string_view key;    // `set KEY`, and the flag --KEY
    std::string_view label;  // the widget's label
    std::string_view help;   // the widget's tooltip and the flag's help
    Kind kind;
    double min = 0.0, max = 0.0;        // valid range (integer, real)
    double ui_min = 0.0, ui_max = 0.0;  // the slider's span; typed values are clamped to min, max
    bool logarithmic = false;           // the slider's scale
    std::span<const ChoiceEntry> choices = {};
    std::string_view choice_what = {};  // the choice's name in messages ("unknown WHAT 'x'")
    bool animation = false;             // only an animated scene has it
    double (*get)(const ViewerState&) = nullptr;
    void (*set)(ViewerState&, double) = nullptr;  // the value checked; may throw InputError
};

std::span<const SettingInfo> viewer_settings();

/// The setting with this key, or null.
const SettingInfo* find_setting(std::string_view key);

/// The value `text` gives the setting (a number, a choice's name); throws InputError naming
/// the setting and what it takes.
double parse_setting(const SettingInfo& info, std::string_view text);

/// Throws InputError unless `value` is one the setting takes (its range, its choices).
double check_setting(const SettingInfo& info, double value);

/// Sets the setting from text (parse_setting()); throws InputError, also when the scene is not
/// animated and the setting is the animation's.
void set_setting(ViewerState& state, const SettingInfo& info, std::string_view text);

/// The setting's value as parse_setting() reads it back.
std::string setting_text(const ViewerState& state, const SettingInfo& info);

/// What the setting takes, for help texts: "0 to 1024", "a|b|c", "0 or 1".
std::string setting_values(const SettingInfo& info);

/// Settings given as text by key (the command line's), applied together.
using GivenSettings = std::map<std::string, std::string, std::less<>>;

/// The flags of the animation's settings among `given` ("--speed, --update"), empty if none.
std::string animation_flags(const GivenSettings& given);

/// Applies the given settings (an empty text: not given) in the table's order; throws
/// InputError.
void apply_settings(ViewerState& state, const GivenSettings& given);

}  // namespace edacrt::app
