// The viewer's settings table (app/settings_table.h): every entry round-trips through the
// script's `set` and through the command line, the ranges are the engine's, the widgets' spans
// lie inside them, and no key means two things.
#include <gtest/gtest.h>

#include <limits>
#include <set>
#include <string>
#include <vector>

#include "input_error.h"
#include "render/film.h"
#include "render/render_settings.h"
#include "setting_flags.h"
#include "settings_table.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

using Kind = SettingInfo::Kind;
using test::error_of;

/// A viewer state with an animated scene, so the animation's settings apply.
ViewerState animated_state() {
    ViewerState s;
    load_into(s, "builtin:cornell", {}, "wave");
    EXPECT_TRUE(s.playback.frames) << s.scene_error;
    return s;
}

/// A valid value of the setting other than the one `s` has.
double other_value(const ViewerState& s, const SettingInfo& info) {
    const double current = info.get(s);
    switch (info.kind) {
        case Kind::choice:
        case Kind::steps:
            for (const ChoiceEntry& c : info.choices)
                if (c.value != current) return c.value;
            break;
        case Kind::toggle:
            return current != 0.0 ? 0.0 : 1.0;
        default:
            if (info.max == std::numeric_limits<double>::max()) return 0.25;  // the time
            return current != info.max ? info.max : info.min;
    }
    ADD_FAILURE() << info.key << " has one value";
    return current;
}

/// The text of `value` as the setting reads it.
std::string text_of(const SettingInfo& info, double value) {
    ViewerState s = animated_state();
    info.set(s, value);
    return setting_text(s, info);
}

TEST(Settings, EveryEntryRoundTripsThroughTheScriptsSet) {
    for (const SettingInfo& info : viewer_settings()) {
        ViewerState s = animated_state();
        const double value = other_value(s, info);
        const std::string text = text_of(info, value);
        EXPECT_EQ(error_of([&] { apply_setting(s, std::string(info.key), text); }), "") << info.key;
        EXPECT_EQ(info.get(s), value) << info.key << " " << text;
        EXPECT_EQ(setting_text(s, info), text) << info.key;
    }
}

TEST(Settings, EveryEntryRoundTripsThroughTheCommandLine) {
    for (const SettingInfo& info : viewer_settings()) {
        ViewerState s = animated_state();
        const double value = other_value(s, info);
        const std::string text = text_of(info, value);
        CLI::App app;
        GivenSettings given;
        add_setting_flags(app, given);
        std::vector<std::string> args = {"edacrt_viewer"};
        const std::string flag = "--" + std::string(info.key);
        if (info.kind == Kind::toggle && value == 1.0)
            args.push_back(flag);  // the flag alone turns it on
        else if (info.kind == Kind::toggle)
            args.push_back(flag + "=" + text);
        else
            args.insert(args.end(), {flag, text});
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        ASSERT_NO_THROW(app.parse(int(argv.size()), argv.data())) << flag << " " << text;
        EXPECT_EQ(animation_flags(given), info.animation ? flag : "") << info.key;
        EXPECT_EQ(error_of([&] { apply_settings(s, given); }), "") << info.key;
        EXPECT_EQ(info.get(s), value) << info.key << " " << text;
    }
}

// A value the setting refuses is refused by `set` and by the flag alike, with the same words.
TEST(Settings, BadValuesAreRefusedByTheFlagAsByTheScript) {
    for (const auto& [key_, text_] :
         std::vector<std::pair<std::string, std::string>>{{"max-depth", "1025"},
                                                          {"spp", "0"},
                                                          {"speed", "9"},
                                                          {"shutter", "-1"},
                                                          {"method", "foo"},
                                                          {"compare-spp", "3"},
                                                          {"time", "nan"}}) {
        const std::string &key = key_, &text = text_;  // lambdas cannot capture bindings (clang 14)
        ViewerState s = animated_state();
        const std::string error = error_of([&] { apply_setting(s, key, text); });
        EXPECT_NE(error, "") << key;
        CLI::App app;
        GivenSettings given;
        add_setting_flags(app, given);
        std::string program = "edacrt_viewer", flag = "--" + key, value = text;
        char* argv[] = {program.data(), flag.data(), value.data()};
        try {
            app.parse(3, argv);
            ADD_FAILURE() << key << " " << text << " was taken";
        } catch (const CLI::ParseError& e) {
            EXPECT_NE(std::string(e.what()).find(error), std::string::npos)
                << e.what() << " / " << error;
        }
    }
}

// The ranges are the ones the engine checks: the largest max depth the renderer takes is the
// largest `set` and the flag take (the slider once stopped at 32 of 1024).
TEST(Settings, RangesAreTheEnginesAndWidgetsSpanInsideThem) {
    const auto renders = [](int max_depth, int ao_samples) {
        RenderSettings settings;
        settings.max_depth = max_depth;
        settings.ao_samples = ao_samples;
        return error_of([&] { validate(settings); }).empty();
    };
    const SettingInfo& depth = *find_setting("max-depth");
    const SettingInfo& ao = *find_setting("ao-samples");
    EXPECT_TRUE(renders(int(depth.min), int(ao.min)));
    EXPECT_TRUE(renders(int(depth.max), int(ao.max)));
    EXPECT_FALSE(renders(int(depth.min) - 1, 4));
    EXPECT_FALSE(renders(int(depth.max) + 1, 4));
    EXPECT_FALSE(renders(8, int(ao.min) - 1));
    EXPECT_FALSE(renders(8, int(ao.max) + 1));
    const SettingInfo& exposure = *find_setting("exposure");
    EXPECT_NO_THROW(validate_exposure(float(exposure.min)));
    EXPECT_NO_THROW(validate_exposure(float(exposure.max)));
    EXPECT_THROW(validate_exposure(float(exposure.max) + 1.0f), InputError);

    const ViewerState defaults;
    for (const SettingInfo& info : viewer_settings()) {
        EXPECT_FALSE(info.help.empty()) << info.key;
        EXPECT_FALSE(info.label.empty()) << info.key;
        if (info.kind == Kind::integer || info.kind == Kind::real) {
            EXPECT_LE(info.min, info.ui_min) << info.key;
            EXPECT_LE(info.ui_max, info.max) << info.key;
            EXPECT_NO_THROW(check_setting(info, info.get(defaults))) << "default of " << info.key;
        }
    }
}

TEST(Settings, ScenesWithoutEmittersStartWithAmbientOcclusionUntilAnIntegratorIsChosen) {
    ViewerState s;
    load_into(s, "builtin:sphere");
    ASSERT_EQ(s.scene_error, "");
    EXPECT_EQ(s.ui.integrator, Integrator::ao);
    load_into(s, "builtin:cornell");
    EXPECT_EQ(s.ui.integrator, Integrator::path);
    apply_setting(s, "integrator", "primary");
    load_into(s, "builtin:sphere");
    EXPECT_EQ(s.ui.integrator, Integrator::primary) << "a choice is kept";
    ViewerState widget;
    const SettingInfo& integrator = *find_setting("integrator");
    integrator.set(widget, double(int(Integrator::path)));  // as the combo sets it
    load_into(widget, "builtin:sphere");
    EXPECT_EQ(widget.ui.integrator, Integrator::path);
}

TEST(Settings, NoKeyMeansTwoThingsAndAnimationSettingsNeedAnAnimation) {
    std::set<std::string_view> keys;
    for (const SettingInfo& info : viewer_settings())
        EXPECT_TRUE(keys.insert(info.key).second) << info.key;
    for (const ParamInfo& info : edacrt_param_info())
        EXPECT_TRUE(keys.insert(info.key).second) << info.key << " is a setting and a parameter";
    ViewerState still;
    EXPECT_EQ(error_of([&] { apply_setting(still, "speed", "2"); }),
              "'speed' needs an animated scene");
    EXPECT_EQ(error_of([&] { apply_setting(still, "no-such-key", "1"); }),
              "unknown setting 'no-such-key'");
    GivenSettings given = {{"speed", "2"}, {"play", "1"}, {"spp", "4"}};
    EXPECT_EQ(animation_flags(given), "--play, --speed") << "in the table's order";
}

}  // namespace
}  // namespace edacrt::app
