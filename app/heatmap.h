#pragma once
// Per-pixel heat maps of a batch's statistics (what a pixel cost), and the colour ramp
// the display shader and the legend share.
#include <glm/vec3.hpp>
#include <span>
#include <string_view>
#include <vector>

#include "trace/trace_stats.h"
#include "util/enum_table.h"

namespace edacrt::app {

/// What the image shows: the render, or one per-pixel count of the analysed batch.
/// The names are the script's (`view NAME`), the help the heat map tab's labels.
enum class View { render, box_tests, triangle_tests, depth, order_misses };
inline constexpr auto kViews =
    enum_table<View>("view", {{View::render, "render", "render"},
                              {View::box_tests, "box", "ray-box tests"},
                              {View::triangle_tests, "triangle", "ray-triangle tests"},
                              {View::depth, "depth", "recursion depth"},
                              {View::order_misses, "order", "traversal-order misses"}});

/// Which recursion the heat map shows when the recording is compared with another (the
/// Recursion tab's "against"): the recording (A), the other (B), or B - A per pixel.
enum class HeatOf { a, b, difference };
inline constexpr auto kHeatOf =
    enum_table<HeatOf>("heat-of", {{HeatOf::a, "a", "A (the recording)"},
                                   {HeatOf::b, "b", "B (against)"},
                                   {HeatOf::difference, "b-a", "B - A"}});

/// One value per pixel (row by row from the top) of `view` from the per-pixel statistics.
std::vector<float> heat_values(std::span<const RayStats> pixels, View view);

/// Turbo (Mikhailov 2019, polynomial fit): a perceptual rainbow for t in [0, 1]. The display
/// shader evaluates the same polynomial.
glm::vec3 turbo(float t);

/// The difference ramp for t in [-1, 1]: blue (B makes fewer tests than A) through white (as
/// many) to red (more). The display shader evaluates the same.
glm::vec3 diverging(float t);

}  // namespace edacrt::app
