#include "setting_flags.h"

#include "util/error.h"
#include "viewer_state.h"

namespace edacrt::app {

void add_setting_flags(CLI::App& app, GivenSettings& given) {
    const ViewerState defaults;
    for (const SettingInfo& info : viewer_settings()) {
        const std::string flag = "--" + std::string(info.key);
        std::string& text = given[std::string(info.key)];
        const CLI::Validator check(
            [&info](std::string& value) -> std::string {
                try {
                    parse_setting(info, value);
                    return {};
                } catch (const InputError& e) {
                    return e.what();
                }
            },
            std::string(info.key) == "time" ? "SECONDS" : "");
        const std::string help = std::string(info.help) + " (" + setting_values(info) + ")";
        CLI::Option* option = info.kind == SettingInfo::Kind::toggle
                                  ? app.add_flag(flag + "{1}", text, help)
                                  : app.add_option(flag, text, help);
        option->check(check);
        if (info.animation) option->group("Animation");
        if (info.kind != SettingInfo::Kind::toggle && !info.animation)
            option->default_str(setting_text(defaults, info));
    }
}

}  // namespace edacrt::app
