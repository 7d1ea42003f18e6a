// EDACRT parameters: a widget with a tooltip for every parameter, generated from their
// descriptions (engine/trace/edacrt_params.h), greyed when the method and the other parameters
// leave it no effect (the tooltip says why); any change re-renders (the viewer compares the
// settings each frame).
#include <imgui.h>

#include <algorithm>
#include <string>

#include "panels.h"

namespace edacrt::app {
namespace {

void tooltip(const ParamInfo& info, const std::string& inert) {
    if (!ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
    if (!inert.empty())
        ImGui::TextColored(ImVec4(1, 0.7f, 0.3f, 1), "no effect now: %s", inert.c_str());
    ImGui::TextUnformatted(info.help.data(), info.help.data() + info.help.size());
    if (info.kind != ParamInfo::Kind::choice)
        ImGui::TextDisabled("range %g to %g", info.min, info.max);
    ImGui::TextDisabled("--%.*s", int(info.key.size()), info.key.data());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

void widget(ViewerState& s, const ParamInfo& info) {
    EdacrtParams& p = s.ui.params;
    const std::string inert = param_inert_reason(s.ui, info);
    ImGui::BeginDisabled(!inert.empty());
    const std::string label(info.label);
    const double value = info.get(p);
    switch (info.kind) {
        case ParamInfo::Kind::integer: {
            // ImGui edits an int; the widest ranges (the seed) are clamped to what it holds.
            const double high = std::min(info.max, 2147483647.0);
            int v = int(std::min(value, high));
            if (ImGui::InputInt(label.c_str(), &v))
                info.set(p, std::clamp(double(v), info.min, high));
            break;
        }
        case ParamInfo::Kind::real: {
            auto v = float(value);
            if (ImGui::SliderFloat(label.c_str(), &v, float(info.min), float(info.ui_max)))
                info.set(p, std::clamp(double(v), info.min, info.max));
            break;
        }
        case ParamInfo::Kind::choice: {
            const std::string_view current = info.choices[std::size_t(value)];
            if (ImGui::BeginCombo(label.c_str(), std::string(current).c_str())) {
                for (std::size_t i = 0; i < info.choices.size(); ++i) {
                    const std::string name(info.choices[i]);
                    if (ImGui::Selectable(name.c_str(), i == std::size_t(value)))
                        info.set(p, double(i));
                }
                ImGui::EndCombo();
            }
            break;
        }
    }
    ImGui::EndDisabled();
    report_item(s, "EDACRT/" + std::string(info.key));
    tooltip(info, inert);
}

}  // namespace

void draw_params_tab(ViewerState& s) {
    EdacrtParams& p = s.ui.params;
    if (s.ui.method != Method::edacrt && s.ui.method != Method::dacrt)
        ImGui::TextDisabled("(used by edacrt and dacrt only)");
    else if (s.ui.method == Method::dacrt)
        ImGui::TextDisabled("(dacrt: hit ratio, order and filter skipping are DACRT's)");
    ImGui::TextUnformatted("preset:");
    for (std::string_view name : preset_names()) {
        ImGui::SameLine();
        if (ImGui::SmallButton(std::string(name).c_str())) p = preset_params(name);
    }
    float label = 0.0f;
    for (const ParamInfo& info : edacrt_param_info())
        label = std::max(label, ImGui::CalcTextSize(std::string(info.label).c_str()).x);
    ImGui::PushItemWidth(-label - ImGui::GetStyle().ItemSpacing.x);
    for (const ParamInfo& info : edacrt_param_info()) widget(s, info);
    ImGui::PopItemWidth();
}

}  // namespace edacrt::app
