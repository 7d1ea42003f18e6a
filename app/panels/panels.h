#pragma once
// The viewer's panels: immediate-mode drawing of the ViewerState (ImGui, needs a frame).
#include <imgui.h>

#include <string>

#include "columns.h"
#include "settings_table.h"
#include "util/enum_table.h"
#include "viewer_state.h"

namespace edacrt::app {

// The two panels (app/panels/panels.cpp) and their tabs, one file each under panels/.
void draw_controls(ViewerState& state);
void draw_analysis(ViewerState& state, float heat_max);
void draw_help(ViewerState& state);
void draw_scene_tab(ViewerState& state);
void draw_camera_tab(ViewerState& state);
void draw_render_tab(ViewerState& state);
void draw_params_tab(ViewerState& state);
void draw_stats_tab(ViewerState& state);
void draw_heatmap_tab(ViewerState& state, float heat_max);
void draw_recursion_tab(ViewerState& state);
void draw_traversal_tab(ViewerState& state);
void draw_frames_tab(ViewerState& state);
/// The animation's timeline under the image (play, pause, scrub, speed); nothing for a still
/// scene.
void draw_timeline(ViewerState& state);
/// The Scene tab's animation settings: which deformation, how tracers take frames, motion blur.
void draw_animation_settings(ViewerState& state);
/// The "compare methods" button and the table of every method's update and trace times.
void draw_comparison(ViewerState& state);
/// The batch Statistics, Heat map, Recursion and Traversal analyse: a combo of the pass's
/// batches, the one before and after, and whether it is recorded yet.
void draw_batch_chooser(ViewerState& state);
/// The value under the cursor while a heat map is shown (a tooltip over the image).
void draw_heat_readout(const ViewerState& state);

/// The explorer's region over the image: the rectangle being dragged (region picking), and,
/// while the Recursion tab shows a recording of a region, that region.
void draw_region(ViewerState& state);

/// While a scene is read: its name and the seconds so far, centred over the image region (the
/// previous scene's image stays under it).
void draw_loading(ViewerState& state);

/// Draws a box's projected edges over the image region (background draw list, clipped to it).
void draw_box_overlay(const ViewerState& state, const Analysis& analysis, const Aabb& box,
                      unsigned colour, float thickness = 1.0f);
/// Where image pixel (x, y) of a width x height image appears in the window.
ImVec2 image_to_window(const ViewerState& state, float x, float y, int width, int height);

/// A combo box of an enum's names (util/enum_table.h), each with its help as a tooltip.
/// Returns true when the user chose another value.
template <typename E, std::size_t N>
bool enum_combo(const char* label, E& value, const EnumTable<E, N>& table) {
    bool changed = false;
    if (ImGui::BeginCombo(label, std::string(enum_name(table, value)).c_str())) {
        for (const EnumEntry<E>& entry : table) {
            if (ImGui::Selectable(std::string(entry.name).c_str(), entry.value == value)) {
                changed = entry.value != value;
                value = entry.value;
            }
            if (!entry.help.empty() && ImGui::IsItemHovered())
                ImGui::SetTooltip("%.*s", int(entry.help.size()), entry.help.data());
        }
        ImGui::EndCombo();
    }
    return changed;
}

/// How a setting's widget departs from its entry: another label ("##x" hides it), a format,
/// the name it is reported as (report_item()).
struct WidgetStyle {
    const char* label = nullptr;
    const char* format = nullptr;
    const char* report = nullptr;
};

/// The widget of setting `key` (viewer_settings()), with its tooltip; an edit is clamped to
/// the setting's valid range. Returns true when the value changed.
bool setting_widget(ViewerState& state, std::string_view key, const WidgetStyle& style = {});

/// A tooltip for the last item, wrapped at a readable width.
void wrapped_tooltip(const std::string& text);

/// An error, wrapped, in red; reported as the item `name` and as an error shown.
void error_text(ViewerState& state, const char* name, const std::string& text);

/// Reports where the last item was drawn, as `name` ("Tab/widget"), for the script's
/// `layout FILE`.
void report_item(ViewerState& state, std::string name);

/// Sets up `columns` in the current table, freezes the header row (and `frozen_columns`), and
/// draws the headers, each with its tooltip. With `compact`, the detail columns are hidden
/// (their cells are skipped).
void table_headers(std::span<const Column> columns, int frozen_columns = 0, bool compact = false);

/// A table cell's text (nothing in a hidden column); counts cells too narrow for it (the layout
/// check reports them).
void cell_text(const char* format, ...) IM_FMTARGS(1);
/// Cells clipped since the last call.
int take_clipped_cells();

}  // namespace edacrt::app
