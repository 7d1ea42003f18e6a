#pragma once
// The viewer's fixed layout, computed from the window size every frame (ImGui 1.86 has no
// docking): controls in a left column, analysis below the image, the image in a region no
// panel overlaps. Pure geometry, tested headless.
#include <cstdint>
#include <string>
#include <vector>

namespace edacrt::app {

struct Rect {
    float x = 0.0f, y = 0.0f, w = 0.0f, h = 0.0f;

    bool operator==(const Rect&) const = default;

    float right() const { return x + w; }
    float bottom() const { return y + h; }
    bool empty() const { return !(w > 0.0f && h > 0.0f); }
    /// True when the interiors share area (touching edges do not count).
    bool overlaps(const Rect& o) const {
        return !empty() && !o.empty() && x < o.right() && o.x < right() && y < o.bottom() &&
               o.y < bottom();
    }
    /// True when `o` lies within this rectangle (up to `slack` pixels of rounding).
    bool contains(const Rect& o, float slack = 0.5f) const {
        return o.x >= x - slack && o.y >= y - slack && o.right() <= right() + slack &&
               o.bottom() <= bottom() + slack;
    }
};

struct LayoutOptions {
    float width = 0.0f, height = 0.0f;  // the window, in ImGui's units
    float em = 13.0f;                   // the font size: panel sizes scale with it
    float title_height = 19.0f;         // a collapsed panel's title bar
    bool panels_hidden = false;         // Tab / F1: the image fills the window
    bool analysis_open = true;          // collapsed: only its title bar stays
    bool animated = false;              // a timeline bar under the image
    float analysis_share = 0.0f;        // the open analysis's share of the height (dragged);
                                        // 0: sized to its tables
};

/// The shares of the height the analysis may be dragged to: the image keeps a sixth.
inline constexpr float kMinAnalysisShare = 0.1f, kMaxAnalysisShare = 5.0f / 6.0f;

struct Layout {
    Rect controls;  // left column, full height
    Rect analysis;  // below the image, right of the controls
    Rect image;     // the rest; never empty while the window is not
    Rect timeline;  // under the image, as wide (animated scenes; else empty)
};

Layout compute_layout(const LayoutOptions& options);

/// Where a panel ended up (queried from ImGui after drawing) and what it could not show.
struct PanelPlacement {
    std::string name;
    Rect rect;
    int clipped_cells = 0;  // table cells whose text was wider than the cell
    // The widths of its table cells, hashed: changes while ImGui fits columns to their text.
    std::uint64_t cell_widths = 0;
    std::string first_clipped = {};  // the first clipped cell's text and widths, for the report
};

/// A widget or window the panels report where it was drawn (the script's `layout FILE`).
struct NamedRect {
    std::string name;
    Rect rect;

    bool operator==(const NamedRect&) const = default;
};

/// The layout's defects: panels that overlap the image or leave the window, clipped cells.
/// Empty when the frame is fine.
std::vector<std::string> layout_problems(const Layout& layout, float width, float height,
                                         const std::vector<PanelPlacement>& panels);

}  // namespace edacrt::app
