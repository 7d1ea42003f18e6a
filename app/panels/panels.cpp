// The two panels of the fixed layout (app/layout.h): the controls column and the analysis
// area, each a window pinned to its rectangle with a tab per subject; and the table-cell
// helper whose clipping the layout check counts.
#include "panels.h"

#include <imgui.h>

#include <algorithm>
#include <bit>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <string>

namespace edacrt::app {
namespace {

int clipped_cells = 0;
std::uint64_t cell_widths = 0;  // FNV-1a over the cells' widths
std::string first_clipped;      // the first clipped cell's text and width

constexpr ImGuiWindowFlags kPinned = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                     ImGuiWindowFlags_NoSavedSettings |
                                     ImGuiWindowFlags_NoBringToFrontOnFocus;

void pin(const Rect& r) {
    ImGui::SetNextWindowPos(ImVec2(r.x, r.y), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(r.w, r.h), ImGuiCond_Always);
}

/// Where the window ended up, for the layout check.
void place(ViewerState& s, const char* name) {
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    const std::uint64_t widths = cell_widths;
    std::string first = std::exchange(first_clipped, std::string());
    s.placements.push_back(
        {name, {pos.x, pos.y, size.x, size.y}, take_clipped_cells(), widths, std::move(first)});
}

/// A tab; the script's `tab NAME` brings it forward. ImGui selects it in the next frame, so
/// the request stays (and waits see it pending) until the tab is drawn open.
bool tab(ViewerState& s, const char* name) {
    const bool select = std::ranges::find(s.select_tabs, name) != s.select_tabs.end();
    const bool open =
        ImGui::BeginTabItem(name, nullptr, select ? ImGuiTabItemFlags_SetSelected : 0);
    report_item(s, std::string(name) + "/tab");
    if (open) {
        s.tabs_open.emplace_back(name);
        std::erase(s.select_tabs, std::string(name));
    }
    return open;
}

/// The analysis's title bar is the split between it and the image: dragging it up or down sets
/// the analysis's share of the window's height for the next frame's layout. A click that does
/// not drag leaves it; its arrow still collapses the analysis.
void drag_split(ViewerState& s) {
    const ImGuiIO& io = ImGui::GetIO();
    const ImVec2 lo = ImGui::GetWindowPos();
    const ImVec2 hi(lo.x + ImGui::GetWindowWidth(), lo.y + ImGui::GetFrameHeight());
    const bool on_title = ImGui::IsWindowHovered() && ImGui::IsMouseHoveringRect(lo, hi, false);
    if (!s.analysis_open || !ImGui::IsMouseDown(ImGuiMouseButton_Left)) s.dragging_split = false;
    if (!s.analysis_open) return;
    if (on_title || s.dragging_split) ImGui::SetMouseCursor(ImGuiMouseCursor_ResizeNS);
    if (on_title && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) s.dragging_split = true;
    if (s.dragging_split && io.DisplaySize.y > 0.0f &&
        ImGui::IsMouseDragging(ImGuiMouseButton_Left))
        s.analysis_share = std::clamp(1.0f - io.MousePos.y / io.DisplaySize.y, kMinAnalysisShare,
                                      kMaxAnalysisShare);
}

}  // namespace

void cell_text(const char* format, ...) {
    char text[256];
    va_list args;
    va_start(args, format);
    std::vsnprintf(text, sizeof text, format, args);
    va_end(args);
    if (ImGui::TableGetColumnCount() > 0 &&
        !(ImGui::TableGetColumnFlags() & ImGuiTableColumnFlags_IsEnabled))
        return;
    // Columns size to their content from the previous frame: a cell is clipped when its text
    // is wider than what is left of it. Only in a column on screen: ImGui refits a column
    // scrolled out of view when it comes back, so a timing that grew while its column was out
    // of view ('13.82', 35 pixels in a column of 28) failed the layout check 1 run in 16
    // under load.
    const bool shown = ImGui::TableGetColumnCount() == 0 ||
                       (ImGui::TableGetColumnFlags() & ImGuiTableColumnFlags_IsVisible);
    const float width = ImGui::GetContentRegionAvail().x;
    if (const float wide = ImGui::CalcTextSize(text).x;
        shown && wide > width + 1.0f && !clipped_cells++)
        first_clipped = "'" + std::string(text) + "', " + std::to_string(int(wide)) + " wide in " +
                        std::to_string(int(width));
    if (shown) cell_widths = (cell_widths ^ std::bit_cast<std::uint32_t>(width)) * 1099511628211ull;
    ImGui::TextUnformatted(text);
}

void table_headers(std::span<const Column> columns, int frozen_columns, bool compact) {
    for (const Column& c : columns)
        ImGui::TableSetupColumn(c.name, compact && c.detail ? ImGuiTableColumnFlags_Disabled : 0);
    ImGui::TableSetupScrollFreeze(frozen_columns, 1);
    ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
    for (const Column& c : columns) {
        ImGui::TableNextColumn();
        ImGui::TableHeader(c.name);
        wrapped_tooltip(c.help);
    }
}

void wrapped_tooltip(const std::string& text) {
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

void error_text(ViewerState& s, const char* name, const std::string& text) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.4f, 0.4f, 1));
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopStyleColor();
    report_item(s, name);
    s.errors_shown.push_back(text);
}

void report_item(ViewerState& s, std::string name) {
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    s.items.push_back({std::move(name), {lo.x, lo.y, hi.x - lo.x, hi.y - lo.y}});
}

int take_clipped_cells() {
    cell_widths = 0;
    first_clipped.clear();
    return std::exchange(clipped_cells, 0);
}

void draw_controls(ViewerState& s) {
    if (s.layout.controls.empty()) return;
    pin(s.layout.controls);
    ImGui::Begin("Controls", nullptr, kPinned | ImGuiWindowFlags_NoCollapse);
    take_clipped_cells();
    if (ImGui::BeginTabBar("controls")) {
        if (tab(s, "Scene")) {
            draw_scene_tab(s);
            ImGui::EndTabItem();
        }
        if (tab(s, "Camera")) {
            draw_camera_tab(s);
            ImGui::EndTabItem();
        }
        if (tab(s, "Render")) {
            draw_render_tab(s);
            ImGui::EndTabItem();
        }
        if (tab(s, "EDACRT")) {
            draw_params_tab(s);
            ImGui::EndTabItem();
        }
        // Where help is: the keys and the mouse are otherwise only in the overlay itself.
        if (ImGui::TabItemButton("? help", ImGuiTabItemFlags_Trailing)) s.show_help = !s.show_help;
        wrapped_tooltip(
            "Mouse and keys (H or ?); hover any control or column header for what "
            "it means");
        report_item(s, "Controls/help");
        ImGui::EndTabBar();
    }
    place(s, "Controls");
    ImGui::End();
}

void draw_analysis(ViewerState& s, float heat_max) {
    if (s.layout.analysis.empty()) return;
    pin(s.layout.analysis);
    ImGui::SetNextWindowCollapsed(!s.analysis_open, ImGuiCond_Always);
    const bool open = ImGui::Begin("Analysis", nullptr, kPinned);
    // The title bar's arrow collapses it; the next frame's layout gives the image the room.
    s.analysis_open = !ImGui::IsWindowCollapsed();
    drag_split(s);
    take_clipped_cells();
    if (open && ImGui::BeginTabBar("analysis")) {
        if (tab(s, "Statistics")) {
            draw_batch_chooser(s);
            draw_stats_tab(s);
            ImGui::EndTabItem();
        }
        if (tab(s, "Heat map")) {
            draw_batch_chooser(s);
            draw_heatmap_tab(s, heat_max);
            ImGui::EndTabItem();
        }
        if (tab(s, "Recursion")) {
            draw_batch_chooser(s);
            draw_recursion_tab(s);
            ImGui::EndTabItem();
        }
        if (tab(s, "Traversal")) {
            draw_batch_chooser(s);
            draw_traversal_tab(s);
            ImGui::EndTabItem();
        }
        if (tab(s, "Frames")) {
            draw_frames_tab(s);
            ImGui::EndTabItem();
        }
        ImGui::EndTabBar();
    }
    place(s, "Analysis");
    ImGui::End();
}

}  // namespace edacrt::app
