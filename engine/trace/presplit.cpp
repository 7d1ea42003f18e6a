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

/// The box of the three corners.
Aabb exact_bounds(const Triangle& tri) {
    Aabb box;
    box.extend(tri.p0);
    box.extend(tri.p1);
    box.extend(tri.p2);
    return box;
}

/// What conservative_bounds adds on every side: 2^-20 of the largest coordinate magnitude of
/// the triangle's exact box.
float conservative_padding(const Aabb& exact) {
    const glm::vec3 magnitude = glm::max(glm::abs(exact.lo), glm::abs(exact.hi));
    return std::max({magnitude.x, magnitude.y, magnitude.z}) * 0x1p-20f;
}

constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
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

/// The box of the triangle's part inside `region` (Sutherland-Hodgman against its six planes).
Box clip(const Triangle& tri, const Box& region) {
    std::array<glm::dvec3, 9> polygon{glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)};
    std::array<glm::dvec3, 9> next;
    std::size_t size = 3;
    for (int axis = 0; axis < 3 && size > 0; ++axis) {
        for (const int side : {0, 1}) {  // keep x >= lo, then x <= hi
            const double plane = side == 0 ? region.lo[axis] : region.hi[axis];
            const auto inside = [&](const glm::dvec3& p) {
                return side == 0 ? p[axis] >= plane : p[axis] <= plane;
            };
            std::size_t kept = 0;
            for (std::size_t i = 0; i < size; ++i) {
                const glm::dvec3& a = polygon[i];
                const glm::dvec3& b = polygon[(i + 1) % size];
                if (inside(a)) next[kept++] = a;
                if (inside(a) != inside(b)) {  // the edge crosses the plane: add the crossing
                    glm::dvec3 p = a + (b - a) * ((plane - a[axis]) / (b[axis] - a[axis]));
                    p[axis] = plane;
                    next[kept++] = p;
                }
            }
            assert(kept <= polygon.size());
            polygon = next;
            size = kept;
        }
    }
    Box box;
    for (std::size_t i = 0; i < size; ++i) {
        box.lo = glm::min(box.lo, polygon[i]);
        box.hi = glm::max(box.hi, polygon[i]);
    }
    return box;
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

/// Cuts one triangle into `pieces` references (fewer if it cannot be cut further; the unused
/// slots keep prim = kUnused).
class Splitter {
  public:
    Splitter(const Box& scene) : scene_(scene) {}

    void split(const Triangle& tri, std::uint32_t prim, std::uint32_t pieces,
               std::span<PrimReference> out) const {
        const Aabb exact = exact_bounds(tri);
        split(tri, prim, conservative_padding(exact), to_double(exact), to_double(exact), pieces,
              out);
    }

  private:
    void split(const Triangle& tri, std::uint32_t prim, float pad, const Box& region,
               const Box& piece, std::uint32_t pieces, std::span<PrimReference> out) const {
        const glm::dvec3 extent = piece.hi - piece.lo;
        const int axis =
            extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
        if (pieces == 1 || !(extent[axis] > 0.0)) {
            out[0] = {widen(piece, pad), prim};
            return;
        }
        const double plane = grid_plane(axis, piece.lo[axis], piece.hi[axis]);
        Box left_region = region, right_region = region;
        left_region.hi[axis] = plane;
        right_region.lo[axis] = plane;
        const Box left = clip(tri, left_region), right = clip(tri, right_region);
        if (left.empty() || right.empty()) {  // rounding in the clip: keep the piece whole
            out[0] = {widen(piece, pad), prim};
            return;
        }
        const double left_area = left.surface_area(), total = left_area + right.surface_area();
        const double share = total > 0.0 ? left_area / total : 0.5;
        const std::uint32_t left_pieces =
            std::clamp(std::uint32_t(std::lround(share * pieces)), 1u, pieces - 1);
        split(tri, prim, pad, left_region, left, left_pieces, out.first(left_pieces));
        split(tri, prim, pad, right_region, right, pieces - left_pieces, out.subspan(left_pieces));
    }

    /// The coarsest plane of the grid over the scene box (cells of 1/2^level of its extent)
    /// strictly between lo and hi, so that pieces of neighbouring triangles line up with the
    /// top-down build's splits; the middle when none is that coarse.
    double grid_plane(int axis, double lo, double hi) const {
        const double origin = scene_.lo[axis], extent = scene_.hi[axis] - origin;
        for (int level = 1; level <= kGridLevels; ++level) {
            const double cell = std::ldexp(extent, -level);
            const double plane = origin + (std::floor((lo - origin) / cell) + 1.0) * cell;
            if (plane > lo && plane < hi) return plane;
        }
        return 0.5 * (lo + hi);
    }

    Box scene_;
};

/// Pieces per triangle: 1 + floor(scale * area), the scale the largest (found by bisection)
/// that keeps the extra pieces within the budget and gives none to a box smaller than
/// `min_area`. Only boxes of at least `min_area` can get pieces, so the bisection counts over
/// those alone.
std::vector<std::uint32_t> piece_counts(std::span<const double> areas, std::size_t budget,
                                        double min_area) {
    std::vector<std::uint32_t> counts(areas.size(), 1);
    std::vector<std::uint32_t> large;  // the triangles that may be cut
    double largest = 0.0;
    for (std::size_t i = 0; i < areas.size(); ++i) {
        largest = std::max(largest, areas[i]);
        if (areas[i] >= min_area && areas[i] > 0.0) large.push_back(std::uint32_t(i));
    }
    if (!(largest > 0.0) || budget == 0 || large.empty()) return counts;
    const auto pieces = [&](double scale, std::size_t i) {
        const double extra = std::floor(scale * areas[i]);
        return 1u + std::uint32_t(std::min(extra, double(kMaxPieces - 1)));
    };
    const auto extra_pieces = [&](double scale) {
        std::size_t sum = 0;
        for (const std::uint32_t i : large) sum += pieces(scale, i) - 1;
        return sum;
    };
    // At scale 1 / min_area a box of min_area gets its first extra piece. (Where the bisection
    // tries a larger scale, the count over `large` already exceeds the budget at 1 / min_area,
    // as the count over all would: the same decisions.)
    double lo = 0.0, hi = double(budget + 1) / largest;  // hi gives the largest alone > budget
    if (min_area > 0.0 && 1.0 / min_area < hi && extra_pieces(1.0 / min_area) <= budget)
        lo = 1.0 / min_area;
    else
        for (int iteration = 0; iteration < 40; ++iteration) {
            const double mid = 0.5 * (lo + hi);
            (extra_pieces(mid) <= budget ? lo : hi) = mid;
        }
    for (const std::uint32_t i : large) counts[i] = pieces(lo, i);
    return counts;
}

}  // namespace

Aabb clipped_bounds(const Triangle& tri, const Aabb& region) {
    const Box piece = clip(tri, to_double(region));
    if (piece.empty()) return {};
    return widen(piece, conservative_padding(exact_bounds(tri)));
}

FrameVector<PrimReference> presplit_references(std::span<const Triangle> triangles, float extra) {
    const std::size_t budget = std::size_t(std::max(0.0f, extra) * float(triangles.size()));
    if (budget == 0) return {};
    std::vector<double> areas(triangles.size());
    // One parallel pass: the areas, their sum and largest, and the scene box (deterministic: the
    // same sum, so the same pieces, for any thread count).
    struct Sums {
        double total = 0.0, largest = 0.0;
        Box scene;
    };
    const Sums sums = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, triangles.size(), 4096), Sums{},
        [&](const tbb::blocked_range<std::size_t>& range, Sums sum) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const Box box = to_double(exact_bounds(triangles[i]));
                const double area = box.surface_area();
                areas[i] = std::isfinite(area) ? area : 0.0;  // (loaders refuse such corners)
                sum.total += areas[i];
                sum.largest = std::max(sum.largest, areas[i]);
                sum.scene.lo = glm::min(sum.scene.lo, box.lo);
                sum.scene.hi = glm::max(sum.scene.hi, box.hi);
            }
            return sum;
        },
        [](Sums a, const Sums& b) {
            a.total += b.total;
            a.largest = std::max(a.largest, b.largest);
            a.scene.lo = glm::min(a.scene.lo, b.scene.lo);
            a.scene.hi = glm::max(a.scene.hi, b.scene.hi);
            return a;
        });
    const double min_area = kMinSplitArea * sums.total / double(triangles.size());
    // A mesh of alike triangles has none to cut: no need to share out the budget.
    if (!(sums.largest >= min_area)) return {};
    const Box& scene = sums.scene;
    const std::vector<std::uint32_t> counts = piece_counts(areas, budget, min_area);
    if (std::all_of(counts.begin(), counts.end(), [](std::uint32_t c) { return c == 1; }))
        return {};  // nothing to cut: the caller uses the triangles themselves
    std::vector<std::size_t> offsets(triangles.size() + 1, 0);
    for (std::size_t i = 0; i < triangles.size(); ++i) offsets[i + 1] = offsets[i] + counts[i];
    FrameVector<PrimReference> references(offsets.back(), PrimReference{Aabb{}, kUnused});
    const Splitter splitter(scene);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                              const std::span<PrimReference> out(references.data() + offsets[i],
                                                                 counts[i]);
                              if (counts[i] == 1)
                                  out[0] = {conservative_bounds(triangles[i]), std::uint32_t(i)};
                              else
                                  splitter.split(triangles[i], std::uint32_t(i), counts[i], out);
                          }
                      });
    std::erase_if(references, [](const PrimReference& r) { return r.prim == kUnused; });
    return references;
}

}  // namespace edacrt
