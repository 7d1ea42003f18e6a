#include "settings_table.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <type_traits>

#include "render/film.h"
#include "render/render_limits.h"
#include "trace/tracer.h"
#include "util/error.h"
#include "util/exact_text.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

using Kind = SettingInfo::Kind;

/// The member at the end of a path of member pointers: member<&A::b, &B::c>(a) is a.b.c.
template <auto First, auto... Rest, typename T>
constexpr auto& member(T& object) {
    if constexpr (sizeof...(Rest) == 0)
        return object.*First;
    else
        return member<Rest...>(object.*First);
}

/// A field as a double; an enum as its value.
template <auto... Path>
double get_field(const ViewerState& s) {
    const auto& field = member<Path...>(s);
    if constexpr (std::is_enum_v<std::remove_cvref_t<decltype(field)>>)
        return double(int(field));
    else
        return double(field);
}

template <auto... Path>
void set_field(ViewerState& s, double value) {
    auto& field = member<Path...>(s);
    using T = std::remove_reference_t<decltype(field)>;
    if constexpr (std::is_enum_v<T>)
        field = static_cast<T>(int(value));
    else if constexpr (std::is_same_v<T, bool>)
        field = value != 0.0;
    else
        field = T(value);
}

/// An enum's table as choices, in the table's order (aliases after a value's first name).
template <const auto& Table>
constexpr auto kChoices = [] {
    std::array<ChoiceEntry, Table.size()> choices{};
    for (std::size_t i = 0; i < Table.size(); ++i)
        choices[i] = {int(Table.entries[i].value), Table.entries[i].name, Table.entries[i].help};
    return choices;
}();

constexpr ChoiceEntry kCompareSteps[] = {
    {1, "1", "1 spp"}, {4, "4", "4 spp"}, {16, "16", "16 spp"}};
constexpr ChoiceEntry kPlayScales[] = {
    {1, "1", "full resolution"}, {2, "2", "half resolution"}, {4, "4", "quarter resolution"}};

/// A setting stored in the field at the end of `Path`; the kinds below add their ranges.
template <auto... Path>
constexpr SettingInfo field(std::string_view key, std::string_view label, std::string_view help,
                            Kind kind) {
    return {.key = key,
            .label = label,
            .help = help,
            .kind = kind,
            .get = get_field<Path...>,
            .set = set_field<Path...>};
}

template <auto... Path>
constexpr SettingInfo integer(std::string_view key, std::string_view label, std::string_view help,
                              double min, double max, double ui_max, bool logarithmic = false) {
    SettingInfo info = field<Path...>(key, label, help, Kind::integer);
    info.min = info.ui_min = min;
    info.max = max;
    info.ui_max = ui_max;
    info.logarithmic = logarithmic;
    return info;
}

template <auto... Path>
constexpr SettingInfo real(std::string_view key, std::string_view label, std::string_view help,
                           double min, double max, double ui_min, double ui_max,
                           bool logarithmic = false) {
    SettingInfo info = integer<Path...>(key, label, help, min, max, ui_max, logarithmic);
    info.kind = Kind::real;
    info.ui_min = ui_min;
    return info;
}

template <const auto& Table, auto... Path>
constexpr SettingInfo choice(std::string_view key, std::string_view label, std::string_view help) {
    SettingInfo info = field<Path...>(key, label, help, Kind::choice);
    info.choices = kChoices<Table>;
    info.choice_what = Table.what;
    return info;
}

template <auto... Path>
constexpr SettingInfo steps(std::string_view key, std::string_view label, std::string_view help,
                            std::span<const ChoiceEntry> values) {
    SettingInfo info = field<Path...>(key, label, help, Kind::steps);
    info.choices = values;
    return info;
}

template <auto... Path>
constexpr SettingInfo toggle(std::string_view key, std::string_view label, std::string_view help) {
    SettingInfo info = field<Path...>(key, label, help, Kind::toggle);
    info.max = info.ui_max = 1.0;
    return info;
}

/// The animation's settings: only an animated scene has them.
constexpr SettingInfo animation(SettingInfo info) {
    info.animation = true;
    return info;
}

// Settings whose change does more than store the value.
void set_time(ViewerState& s, double t) {  // shows time t, paused
    s.playback.playing = false;
    seek(s, t);
    if (!s.playback.error.empty()) throw InputError(s.playback.error);
}
void set_integrator(ViewerState& s, double value) {  // a choice every later scene keeps
    s.ui.integrator = Integrator(int(value));
    s.integrator_chosen = true;
}
void set_play(ViewerState& s, double on) {
    s.playback.playing = on != 0.0;
    s.playback.waited = 0.0;
}
double get_shutter(const ViewerState& s) {
    return s.playback.motion_blur ? double(s.playback.shutter) : 0.0;
}
void set_shutter(ViewerState& s, double shutter) {  // 0: no motion blur
    s.playback.motion_blur = shutter > 0.0;
    if (shutter > 0.0) s.playback.shutter = float(shutter);
}

SettingInfo with(SettingInfo info, double (*get)(const ViewerState&),
                 void (*set)(ViewerState&, double)) {
    if (get) info.get = get;
    info.set = set;
    return info;
}

constexpr double kAnyNumber = std::numeric_limits<double>::max();

// In the order the command line applies them: the time before play (which `time` pauses).
const SettingInfo kSettings[] = {
    choice<kMethods, &ViewerState::ui, &UiSettings::method>("method", "method",
                                                            "how rays are traced"),
    choice<kEmbreeModes, &ViewerState::ui, &UiSettings::embree_mode>(
        "embree-mode", "embree mode", "how the embree method hands rays to Embree"),
    with(choice<kIntegrators, &ViewerState::ui, &UiSettings::integrator>(
             "integrator", "integrator",
             "integrator (until one is chosen, path for scenes with emitters, ao for those "
             "without)"),
         nullptr, set_integrator),
    choice<kPrimaryShadings, &ViewerState::ui, &UiSettings::primary>(
        "primary", "shading", "primary: what the camera rays show"),
    integer<&ViewerState::ui, &UiSettings::max_depth>(
        "max-depth", "max depth", "path: bounces after the camera ray", 0, kMaxMaxDepth, 32),
    integer<&ViewerState::ui, &UiSettings::ao_samples>("ao-samples", "ao rays", "ao: rays per hit",
                                                       1, kMaxAoSamples, 64),
    integer<&ViewerState::ui, &UiSettings::spp_target>(
        "spp", "spp", "samples per pixel to accumulate", 1, 1 << 20, 65536, true),
    real<&ViewerState::ui, &UiSettings::resolution_scale>(
        "resolution", "resolution", "render size as a fraction of the image region's pixels", 0.125,
        1, 0.125, 1),
    integer<&ViewerState::ui, &UiSettings::threads>(
        "threads", "threads", "worker threads of the renderer and the tracer (0: all cores)", 0,
        1024, 64),
    integer<&ViewerState::ui, &UiSettings::seed>(
        "seed", "seed",
        "the sample sequence: the same seed gives the same image for every method and thread "
        "count",
        0, std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max()),
    toggle<&ViewerState::ui, &UiSettings::paused>("pause", "pause",
                                                  "hold the render where it is (1: paused)"),
    real<&ViewerState::exposure>("exposure", "exposure",
                                 "display only: radiance times 2^stops before tone mapping",
                                 -kMaxExposure, kMaxExposure, -8, 8),
    choice<kToneMaps, &ViewerState::tone_map>("tone-map", "tone map",
                                              "display only: how radiance above 1 is compressed"),
    real<&ViewerState::font_scale>(
        "font-scale", "font scale",
        "the panels' text and widgets, times the monitor's content scale (Ctrl +, Ctrl -; "
        "Ctrl 0: 1)",
        kMinFontScale, kMaxFontScale, kMinFontScale, kMaxFontScale),
    real<&ViewerState::analysis_share>(
        "analysis-height", "analysis height",
        "the analysis area's share of the window's height (drag its title bar up or down; 0: "
        "sized to its tables)",
        0, kMaxAnalysisShare, 0, kMaxAnalysisShare),
    toggle<&ViewerState::step_playing>(
        "step-play", "play",
        "step-through: advance node by node by itself, at step-rate, to the last node"),
    real<&ViewerState::step_rate>("step-rate", "nodes/s",
                                  "step-through: nodes entered per second while playing", 0.1, 1000,
                                  0.1, 1000, true),
    steps<&ViewerState::compare_spp>(
        "compare-spp", "compare spp",
        "camera rays per pixel, one batch, of `compare`: 1, the pixel centres; more, jittered "
        "rays as `edacrt bench` makes them (the paper traces many rays per batch, where "
        "sampling pays more)",
        kCompareSteps),
    animation(with(real<&ViewerState::playback, &Playback::time>(
                       "time", "time", "the animation's time shown, in seconds (paused)",
                       -kAnyNumber, kAnyNumber, 0, 0),
                   nullptr, set_time)),
    animation(with(toggle<&ViewerState::playback, &Playback::playing>(
                       "play", "play", "play the animation (Space plays or pauses)"),
                   nullptr, set_play)),
    animation(real<&ViewerState::playback, &Playback::speed>(
        "speed", "speed",
        "animation seconds per second. A frame is shown once its first pass is rendered, so a "
        "slow method shows fewer frames, each at its true time.",
        0.05, 4, 0.05, 4, true)),
    animation(toggle<&ViewerState::playback, &Playback::loop>("loop", "loop",
                                                              "at the end, start over (0: stop)")),
    animation(choice<kSceneUpdates, &ViewerState::playback, &Playback::update>(
        "update", "update",
        "how the tracer takes each new frame (edacrt, dacrt and naive keep no structure: "
        "nothing to update)")),
    animation(with(real<&ViewerState::playback, &Playback::shutter>(
                       "shutter", "shutter s",
                       "motion blur: seconds of shutter around the frame's time (0: none); "
                       "passes are rendered at times spread over it and averaged, so the blur "
                       "converges while the animation is paused",
                       0, 1000, 1e-3, 1, true),
                   get_shutter, set_shutter)),
    animation(steps<&ViewerState::playback, &Playback::play_scale>(
        "play-scale", "while playing",
        "frames render at 1/play-scale of the resolution while the animation plays (smoother); "
        "paused, the frame shown renders at full resolution and converges",
        kPlayScales)),
};

std::string number_text(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", x);
    return text;
}

std::string choice_names(const SettingInfo& info, std::string_view separator) {
    std::string names;
    for (const ChoiceEntry& c : info.choices)
        names.append(names.empty() ? "" : separator) += c.name;
    return names;
}

}  // namespace

std::span<const SettingInfo> viewer_settings() { return kSettings; }

const SettingInfo* find_setting(std::string_view key) {
    for (const SettingInfo& info : kSettings)
        if (info.key == key) return &info;
    return nullptr;
}

double check_setting(const SettingInfo& info, double value) {
    const std::string key(info.key);
    switch (info.kind) {
        case Kind::integer:
        case Kind::real:
            if (!(value >= info.min && value <= info.max) ||
                (info.kind == Kind::integer && value != std::floor(value)))
                throw InputError(key + " must be " +
                                 (info.kind == Kind::integer ? "a whole number " : "") + "from " +
                                 number_text(info.min) + " to " + number_text(info.max) + ", got " +
                                 number_text(value));
            return value;
        case Kind::toggle:
            return value != 0.0 ? 1.0 : 0.0;
        case Kind::choice:
        case Kind::steps:
            for (const ChoiceEntry& c : info.choices)
                if (c.value == value) return value;
            throw InputError("'" + key + "' is " + setting_values(info) + ", got '" +
                             number_text(value) + "'");
    }
    return value;
}

double parse_setting(const SettingInfo& info, std::string_view text) {
    if (info.kind == Kind::choice) {
        for (const ChoiceEntry& c : info.choices)
            if (c.name == text) return c.value;
        throw InputError("unknown " + std::string(info.choice_what) + " '" + std::string(text) +
                         "' (known: " + choice_names(info, ", ") + ")");
    }
    const std::optional<double> value = parse_number(text);
    if (!value)
        throw InputError("'" + std::string(info.key) + "' needs a number, got '" +
                         std::string(text) + "'");
    return check_setting(info, *value);
}

void set_setting(ViewerState& s, const SettingInfo& info, std::string_view text) {
    if (info.animation && !s.playback.frames)
        throw InputError("'" + std::string(info.key) + "' needs an animated scene");
    info.set(s, parse_setting(info, text));
}

std::string setting_text(const ViewerState& s, const SettingInfo& info) {
    const double value = info.get(s);
    switch (info.kind) {
        case Kind::choice:
            for (const ChoiceEntry& c : info.choices)
                if (c.value == value) return std::string(c.name);
            return "?";
        case Kind::real:
            return exact_text(value);
        default:
            return std::to_string(std::int64_t(value));
    }
}

std::string setting_values(const SettingInfo& info) {
    switch (info.kind) {
        case Kind::integer:
        case Kind::real:
            if (info.max == kAnyNumber) return "a number";
            return number_text(info.min) + " to " + number_text(info.max);
        case Kind::choice:
            return choice_names(info, "|");
        case Kind::steps: {
            std::string values = choice_names(info, ", ");
            const auto comma = values.rfind(", ");
            return comma == std::string::npos ? values : values.replace(comma, 2, " or ");
        }
        case Kind::toggle:
            return "0 or 1";
    }
    return {};
}

std::string animation_flags(const GivenSettings& given) {
    std::string flags;
    for (const SettingInfo& info : viewer_settings())
        if (const auto it = given.find(info.key);
            info.animation && it != given.end() && !it->second.empty())
            flags += (flags.empty() ? "--" : ", --") + std::string(info.key);
    return flags;
}

void apply_settings(ViewerState& s, const GivenSettings& given) {
    for (const SettingInfo& info : viewer_settings())
        if (const auto it = given.find(info.key); it != given.end() && !it->second.empty())
            set_setting(s, info, it->second);
}

}  // namespace edacrt::app
