// A setting's widget, drawn from its entry in viewer_settings() (app/settings_table.h): the
// kind of widget, its span, its tooltip, and the valid range every edit is clamped to.
#include <imgui.h>

#include <algorithm>
#include <string>

#include "panels.h"

namespace edacrt::app {
namespace {

/// The entry's help, its choices' descriptions, what it takes and its flag.
std::string tooltip_text(const SettingInfo& info) {
    std::string text(info.help);
    if (info.kind == SettingInfo::Kind::choice) {
        text += ":";
        for (const ChoiceEntry& c : info.choices) {
            text.append(c.value == info.choices.front().value ? " " : ", ").append(c.name);
            if (!c.help.empty()) text.append(" (").append(c.help).append(")");
        }
    }
    return text + "\n--" + std::string(info.key) + " " + setting_values(info);
}

/// A combo of the choices (their names, or a step's label), each with its description.
bool choice_combo(const char* label, const SettingInfo& info, double& value) {
    const bool steps = info.kind == SettingInfo::Kind::steps;
    std::string preview = "?";
    for (const ChoiceEntry& c : info.choices)
        if (c.value == value) preview = std::string(steps ? c.help : c.name);
    if (!ImGui::BeginCombo(label, preview.c_str())) return false;
    bool changed = false;
    for (const ChoiceEntry& c : info.choices) {
        if (ImGui::Selectable(std::string(steps ? c.help : c.name).c_str(), c.value == value)) {
            changed = c.value != value;
            value = c.value;
        }
        if (!steps && !c.help.empty() && ImGui::IsItemHovered())
            ImGui::SetTooltip("%.*s", int(c.help.size()), c.help.data());
    }
    ImGui::EndCombo();
    return changed;
}

}  // namespace

bool setting_widget(ViewerState& s, std::string_view key, const WidgetStyle& style) {
    const SettingInfo& info = *find_setting(key);
    const std::string label = style.label ? style.label : std::string(info.label);
    const ImGuiSliderFlags flags = info.logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
    double value = info.get(s);
    bool changed = false;
    switch (info.kind) {
        case SettingInfo::Kind::integer: {
            int v = int(value);
            // A span as wide as an int (the seed) is typed; the others slide.
            changed = info.ui_max >= 2147483647.0
                          ? ImGui::InputInt(label.c_str(), &v)
                          : ImGui::SliderInt(label.c_str(), &v, int(info.ui_min), int(info.ui_max),
                                             style.format ? style.format : "%d", flags);
            value = v;
            break;
        }
        case SettingInfo::Kind::real: {
            auto v = float(value);
            changed = ImGui::SliderFloat(label.c_str(), &v, float(info.ui_min), float(info.ui_max),
                                         style.format ? style.format : "%.3g", flags);
            value = v;
            break;
        }
        case SettingInfo::Kind::choice:
        case SettingInfo::Kind::steps:
            changed = choice_combo(label.c_str(), info, value);
            break;
        case SettingInfo::Kind::toggle: {
            bool on = value != 0.0;
            changed = ImGui::Checkbox(label.c_str(), &on);
            value = on ? 1.0 : 0.0;
            break;
        }
    }
    // Ctrl+click types a value past the slider's span: it is clamped to the valid range.
    const bool ranged =
        info.kind == SettingInfo::Kind::integer || info.kind == SettingInfo::Kind::real;
    if (changed) info.set(s, ranged ? std::clamp(value, info.min, info.max) : value);
    if (style.report) report_item(s, style.report);
    wrapped_tooltip(tooltip_text(info));
    return changed;
}

}  // namespace edacrt::app
