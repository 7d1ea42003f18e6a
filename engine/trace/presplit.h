#pragma once
// Pre-splitting of large triangles into several references (early split clipping, Ernst &
// Greiner 2007, with the budget and grid-aligned planes of Karras & Aila, "Fast Parallel
// Construction of High-Quality Bounding Volume Hierarchies", 2013, Section 5).
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "geometry/triangle.h"

namespace edacrt {

/// Which of a frame's triangles are cut, and into how many pieces: each triangle whose box's
/// surface area is at least twice the mean gets extra pieces in proportion to that area, at most
/// `extra` times the triangle count in all (0: none).
struct PresplitPlan {
    std::vector<std::uint32_t> cut;     // the triangles cut, ascending
    std::vector<std::uint32_t> pieces;  // how many pieces cut[k] becomes (at least 2)
    Aabb grid;                          // the scene box, whose grid the cuts follow
};
/// The surface area of the box of a triangle's corners (corners_bounds()), 0 if that is not
/// finite: the plan's measure of a triangle.
inline float box_area(const Aabb& corners) {
    const glm::vec3 e = corners.hi - corners.lo;
    const float area = 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    return area <= std::numeric_limits<float>::max() ? area : 0.0f;  // (and not NaN)
}

/// The most extra pieces a plan of `triangles` triangles makes: `extra` per triangle. A plan
/// makes at most twice this many pieces in all (each cut triangle has at least one extra).
std::size_t presplit_budget(std::size_t triangles, float extra);

/// `areas[i]`: box_area(corners_bounds()) of triangle i. Serial: the same plan for any thread
/// count.
PresplitPlan plan_presplit(std::span<const float> areas, float extra, const Aabb& grid);

/// Cuts `tri` into out.size() pieces, recursively by the coarsest plane of a grid over
/// plan.grid that crosses its piece's longest axis, the pieces shared in proportion to the
/// halves' areas, and writes each piece's box: that of the part of `tri` inside the cuts, clipped
/// in double, rounded outwards and padded like conservative_bounds(tri), so it holds every point
/// of that part where the watertight test may accept a hit. The union covers
/// conservative_bounds(tri). Returns how many it wrote: fewer when a piece cannot be cut.
std::size_t split_triangle(const Triangle& tri, const Aabb& grid, std::span<Aabb> out);

}  // namespace edacrt
