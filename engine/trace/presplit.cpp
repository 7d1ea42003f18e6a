#include "trace/presplit.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <limits>

namespace edacrt {
namespace {

constexpr std::uint32_t kMaxPieces = 1u << 16;  // per triangle
constexpr int kGridLevels = 30;                 // below this, split at the middle
// Only a triangle whose box's surface area is at least this many times the mean is cut. Pieces
// of a triangle of about the typical size make nodes hold more references without making their
// boxes tighter: on the bunny, whose triangles are all alike, cutting the 28% of them the
// budget reached cost 10 ms per frame and 2-5% more triangle tests. In the buildings every
// triangle the budget reaches has a box over 2.2 times the mean (Sponza 2.6, Sibenik 2.2,
// Conference 3.0), so this changes nothing there.
constexpr double kMinSplitArea = 2.0;

/// A box in double: pieces are clipped and cut without rounding.
struct Box {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()};
    glm::dvec3 hi{-std::numeric_limits<double>::infinity()};

    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    double surface_area() const {
        if (empty()) return 0.0;
        const glm::dvec3 e = hi - lo;
        return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

/// A convex polygon in double: a triangle's part inside a box (at most 9 corners; room for
/// rounding to add a few).
struct Polygon {
    std::array<glm::dvec3, 16> corners;
    std::size_t size = 0;

    Box box() const {
        Box b;
        for (std::size_t i = 0; i < size; ++i) {
            b.lo = glm::min(b.lo, corners[i]);
            b.hi = glm::max(b.hi, corners[i]);
        }
        return b;
    }
};

Polygon corners(const Triangle& tri) {
    Polygon polygon;
    polygon.corners[0] = glm::dvec3(tri.p0);
    polygon.corners[1] = glm::dvec3(tri.p1);
    polygon.corners[2] = glm::dvec3(tri.p2);
    polygon.size = 3;
    return polygon;
}

/// Cuts `polygon` by the plane x[A] = plane into its parts below and above it (one
/// Sutherland-Hodgman step for each side; a crossing is put exactly on the plane, and a corner
/// on the plane belongs to both). False when a part would not fit (it then stays whole). The
/// axis is a template argument so that x[A] is a member, not a switch.
template <int A>
bool cut_on(const Polygon& polygon, double plane, Polygon& below, Polygon& above) {
    below.size = above.size = 0;
    const std::size_t room = polygon.corners.size() - 1;
    for (std::size_t i = 0; i < polygon.size; ++i) {
        const glm::dvec3& a = polygon.corners[i];
        const glm::dvec3& b = polygon.corners[i + 1 == polygon.size ? 0 : i + 1];
        if (below.size >= room || above.size >= room) return false;
        if (a[A] <= plane) below.corners[below.size++] = a;
        if (a[A] >= plane) above.corners[above.size++] = a;
        if ((a[A] < plane && b[A] > plane) || (a[A] > plane && b[A] < plane)) {
            glm::dvec3 p = a + (b - a) * ((plane - a[A]) / (b[A] - a[A]));
            p[A] = plane;
            below.corners[below.size++] = p;
            above.corners[above.size++] = p;
        }
    }
    return true;
}

bool cut(const Polygon& polygon, int axis, double plane, Polygon& below, Polygon& above) {
    return axis == 0   ? cut_on<0>(polygon, plane, below, above)
           : axis == 1 ? cut_on<1>(polygon, plane, below, above)
                       : cut_on<2>(polygon, plane, below, above);
}

/// Rounds outwards to float (the double box stays inside) and pads like conservative_bounds.
Aabb widen(const Box& box, float pad) {
    Aabb out;
    for (int axis = 0; axis < 3; ++axis) {
        float lo = float(box.lo[axis]), hi = float(box.hi[axis]);
        if (double(lo) > box.lo[axis]) lo = std::nextafter(lo, -kInfinity);
        if (double(hi) < box.hi[axis]) hi = std::nextafter(hi, kInfinity);
        out.lo[axis] = lo - pad;
        out.hi[axis] = hi + pad;
    }
    return out;
}

Box to_double(const Aabb& box) { return {glm::dvec3(box.lo), glm::dvec3(box.hi)}; }

/// Cuts one triangle into pieces (see split_triangle).
class Splitter {
  public:
    explicit Splitter(const Box& scene) : scene_(scene) {}

    std::size_t split(const Triangle& tri, std::span<Aabb> out) const {
        const Polygon polygon = corners(tri);
        return split(conservative_padding(corners_bounds(tri)), polygon, polygon.box(), out);
    }

  private:
    /// `piece` is the part of the triangle inside the cuts so far, `box` its box; it gets
    /// out.size() pieces.
    std::size_t split(float pad, const Polygon& piece, const Box& box, std::span<Aabb> out) const {
        const glm::dvec3 extent = box.hi - box.lo;
        const int axis =
            extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
        Polygon below, above;
        if (out.size() == 1 || !(extent[axis] > 0.0) ||
            !cut(piece, axis, grid_plane(axis, box.lo[axis], box.hi[axis]), below, above) ||
            below.size < 3 || above.size < 3) {  // (rounding in the cut: keep the piece whole)
            out[0] = widen(box, pad);
            return 1;
        }
        const Box left = below.box(), right = above.box();
        const double left_area = left.surface_area(), total = left_area + right.surface_area();
        const double share = total > 0.0 ? left_area / total : 0.5;
        const std::size_t pieces = out.size();
        const std::size_t left_pieces = std::clamp(std::size_t(std::lround(share * double(pieces))),
                                                   std::size_t(1), pieces - 1);
        const std::size_t made = split(pad, below, left, out.first(left_pieces));
        // The right half's pieces follow the left half's without a gap.
        return made + split(pad, above, right, out.subspan(made, pieces - left_pieces));
    }

    /// The coarsest plane of the grid over the scene box (cells of 1/2^level of its extent)
    /// strictly between lo and hi, so that pieces of neighbouring triangles line up with the
    /// top-down build's splits; the middle when none is that coarse.
    double grid_plane(int axis, double lo, double hi) const {
        const double origin = scene_.lo[axis];
        double cell = scene_.hi[axis] - origin;
        // (lo - origin) / cell at each level, with one division: cell is the extent times a
        // power of two, and scaling by one commutes with rounding, so this is exact.
        double cells = (lo - origin) / cell;
        for (int level = 1; level <= kGridLevels; ++level) {
            cell *= 0.5;  // extent / 2^level, exactly
            cells *= 2.0;
            const double plane = origin + (std::floor(cells) + 1.0) * cell;
            if (plane > lo && plane < hi) return plane;
        }
        return 0.5 * (lo + hi);
    }

    Box scene_;
};

/// Extra pieces for the triangles that may be cut (box areas `areas`, each at least
/// `min_area`): floor(scale * area), the scale the largest (found by bisection) that keeps the
/// sum within the budget and gives none to a box smaller than `min_area`.
std::vector<std::uint32_t> extra_pieces(std::span<const float> areas, std::size_t budget,
                                        double min_area) {
    const auto extra = [](double scale, float area) {
        return std::min(std::floor(scale * double(area)), double(kMaxPieces - 1));
    };
    const auto total = [&](double scale) {
        double sum = 0.0;  // exact: a sum of integers below 2^53
        for (const float area : areas) sum += extra(scale, area);
        return sum;
    };
    const double largest = *std::max_element(areas.begin(), areas.end());
    // At scale 1 / min_area a box of min_area gets its first extra piece.
    double lo = 0.0, hi = double(budget + 1) / largest;  // hi gives the largest alone > budget
    if (1.0 / min_area < hi && total(1.0 / min_area) <= double(budget))
        lo = 1.0 / min_area;
    else
        for (int iteration = 0; iteration < 40; ++iteration) {
            const double mid = 0.5 * (lo + hi);
            (total(mid) <= double(budget) ? lo : hi) = mid;
        }
    std::vector<std::uint32_t> pieces(areas.size());
    for (std::size_t i = 0; i < areas.size(); ++i) pieces[i] = std::uint32_t(extra(lo, areas[i]));
    return pieces;
}

}  // namespace

std::size_t presplit_budget(std::size_t triangles, float extra) {
    return std::size_t(std::max(0.0f, extra) * float(triangles));
}

PresplitPlan plan_presplit(std::span<const float> areas, float extra, const Aabb& grid) {
    const std::size_t count = areas.size();
    const std::size_t budget = presplit_budget(count, extra);
    if (budget == 0) return {};
    // Serial, so the same sum and the same pieces for any thread count; summed per block of
    // 4096 and then over the blocks, the order in which a parallel pass summed them before
    // (another order rounds differently and may move a triangle across min_area).
    double total = 0.0;
    constexpr std::size_t kBlock = 4096;
    for (std::size_t begin = 0; begin < count; begin += kBlock) {
        double block = 0.0;
        for (std::size_t i = begin; i < std::min(count, begin + kBlock); ++i)
            block += double(areas[i]);
        total += block;
    }
    const double min_area = kMinSplitArea * total / double(count);
    std::vector<std::uint32_t> large;  // the triangles that may be cut
    std::vector<float> large_areas;
    for (std::size_t i = 0; i < areas.size(); ++i)
        if (areas[i] >= min_area && areas[i] > 0.0f) {
            large.push_back(std::uint32_t(i));
            large_areas.push_back(areas[i]);
        }
    // A mesh of alike triangles has none to cut: no need to share out the budget.
    if (large.empty()) return {};
    const std::vector<std::uint32_t> extra_counts = extra_pieces(large_areas, budget, min_area);
    PresplitPlan plan;
    for (std::size_t k = 0; k < large.size(); ++k)
        if (extra_counts[k] != 0) {
            plan.cut.push_back(large[k]);
            plan.pieces.push_back(1 + extra_counts[k]);
        }
    plan.grid = grid;
    return plan;
}

std::size_t split_triangle(const Triangle& tri, const Aabb& grid, std::span<Aabb> out) {
    return Splitter(to_double(grid)).split(tri, out);
}

}  // namespace edacrt
