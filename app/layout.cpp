#include "layout.h"

#include <algorithm>
#include <cstdio>

namespace edacrt::app {

Layout compute_layout(const LayoutOptions& o) {
    Layout layout;
    const float width = std::max(o.width, 0.0f), height = std::max(o.height, 0.0f);
    if (o.panels_hidden) {
        layout.image = {0.0f, 0.0f, width, height};
        return layout;
    }
    // The controls need about 26 characters of widgets and labels; on a narrow window they
    // give up width first (they scroll), so the image keeps at least 45% of it.
    const float controls = std::min(27.0f * o.em, 0.55f * width);
    layout.controls = {0.0f, 0.0f, controls, height};
    const float right = width - controls;
    // The analysis tables want about 14 lines; the image keeps at least 40% of the height,
    // unless the split between them was dragged.
    const float dragged =
        std::clamp(o.analysis_share, kMinAnalysisShare, kMaxAnalysisShare) * height;
    const float analysis =
        !o.analysis_open ? std::min(o.title_height, 0.6f * height)
        : o.analysis_share > 0.0f
            ? std::max(dragged, std::min(o.title_height, height))
            : std::clamp(0.4f * height, std::min(14.0f * o.em, 0.6f * height), 0.6f * height);
    layout.analysis = {controls, height - analysis, right, analysis};
    // The timeline: one row of widgets with the window's padding, while the image keeps at
    // least a third of the height.
    const float timeline =
        o.animated ? std::min(2.0f * o.title_height, (height - analysis) / 3.0f) : 0.0f;
    layout.image = {controls, 0.0f, right, height - analysis - timeline};
    if (o.animated) layout.timeline = {controls, layout.image.bottom(), right, timeline};
    return layout;
}

std::vector<std::string> layout_problems(const Layout& layout, float width, float height,
                                         const std::vector<PanelPlacement>& panels) {
    std::vector<std::string> problems;
    const Rect window{0.0f, 0.0f, width, height};
    const auto describe = [](const Rect& r) {
        char text[96];
        std::snprintf(text, sizeof text, "(%.0f, %.0f, %.0f x %.0f)", r.x, r.y, r.w, r.h);
        return std::string(text);
    };
    if (layout.image.empty()) problems.push_back("the image region is empty");
    for (const PanelPlacement& p : panels) {
        if (!window.contains(p.rect))
            problems.push_back(p.name + " " + describe(p.rect) + " leaves the window " +
                               describe(window));
        if (p.rect.overlaps(layout.image))
            problems.push_back(p.name + " " + describe(p.rect) + " overlaps the image " +
                               describe(layout.image));
        if (p.clipped_cells > 0)
            problems.push_back(p.name + ": " + std::to_string(p.clipped_cells) +
                               " table cells clipped (the first: " + p.first_clipped + ")");
    }
    return problems;
}

}  // namespace edacrt::app
