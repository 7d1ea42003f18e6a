#pragma once
// Pre-splitting of large triangles into several references (early split clipping, Ernst &
// Greiner 2007, with the budget and grid-aligned planes of Karras & Aila, "Fast Parallel
// Construction of High-Quality Bounding Volume Hierarchies", 2013, Section 5).
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/triangle.h"
#include "util/frame_memory.h"

namespace edacrt {

/// A triangle's box, or the box of one of its pieces.
struct PrimReference {
    Aabb box;
    std::uint32_t prim = 0;
};

/// The box of the part of `tri` inside `region`, rounded outwards and padded like
/// conservative_bounds(tri), so it holds every point of that part where the watertight test may
/// accept a hit; clipped in double. Empty when the triangle misses the region.
Aabb clipped_bounds(const Triangle& tri, const Aabb& region);

/// References for the triangles: each triangle whose box's surface area is at least twice the
/// mean gets pieces in proportion to that area, at most `extra` times the triangle count in all
/// (0: one reference per triangle). A triangle
/// with n pieces is cut recursively by the coarsest plane of a grid over the scene box that
/// crosses its piece's longest axis, the pieces shared in proportion to the halves' areas. Every
/// piece's box is clipped_bounds(), so the union covers conservative_bounds(tri). Empty when no
/// triangle is cut (one reference per triangle: use the triangles). Parallel; the result is the
/// same for any thread count.
FrameVector<PrimReference> presplit_references(std::span<const Triangle> triangles, float extra);

}  // namespace edacrt
