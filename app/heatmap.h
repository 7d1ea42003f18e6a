#pragma once
// Per-pixel heat maps of the camera rays' statistics (what a pixel cost), and the colour ramp
// the display shader and the legend share.
#include <glm/vec3.hpp>
#include <string_view>
#include <vector>

#include "trace/trace_stats.h"

namespace edacrt::app {

/// What the image shows: the render, or one per-pixel count of the first pass's camera rays.
enum class View { render, box_tests, triangle_tests, depth, order_misses };
inline constexpr View kViews[] = {View::render, View::box_tests, View::triangle_tests, View::depth,
                                  View::order_misses};
std::string_view view_name(View view);

/// One value per pixel (row by row from the top) of `view` from the per-ray statistics.
std::vector<float> heat_values(const TraceDetail& detail, View view);

/// Turbo (Mikhailov 2019, polynomial fit): a perceptual rainbow for t in [0, 1]. The display
/// shader evaluates the same polynomial.
glm::vec3 turbo(float t);

}  // namespace edacrt::app
