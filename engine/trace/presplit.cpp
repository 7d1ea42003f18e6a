#include "trace/presplit.h"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <bit>
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
/// rounding to add a few), and the box of its corners.
struct Polygon {
    std::array<glm::dvec3, 16> corners;
    std::size_t size = 0;
    Box box;

    void add(const glm::dvec3& corner) {
        corners[size++] = corner;
        box.lo = glm::min(box.lo, corner);
        box.hi = glm::max(box.hi, corner);
    }
};

Polygon corners(const Triangle& tri) {
    Polygon polygon;
    polygon.add(glm::dvec3(tri.p0));
    polygon.add(glm::dvec3(tri.p1));
    polygon.add(glm::dvec3(tri.p2));
    return polygon;
}

/// Cuts `polygon` by the plane x[A] = plane into its parts below and above it (one
/// Sutherland-Hodgman step for each side; a crossing is put exactly on the plane, and a corner
/// on the plane belongs to both). False when a part would not fit (it then stays whole). The
/// axis is a template argument so that x[A] is a member, not a switch.
template <int A>
bool cut_on(const Polygon& polygon, double plane, Polygon& below, Polygon& above) {
    below.size = above.size = 0;
    below.box = above.box = Box{};
    const std::size_t room = polygon.corners.size() - 1;
    for (std::size_t i = 0; i < polygon.size; ++i) {
        const glm::dvec3& a = polygon.corners[i];
        const glm::dvec3& b = polygon.corners[i + 1 == polygon.size ? 0 : i + 1];
        if (below.size >= room || above.size >= room) return false;
        if (a[A] <= plane) below.add(a);
        if (a[A] >= plane) above.add(a);
        if ((a[A] < plane && b[A] > plane) || (a[A] > plane && b[A] < plane)) {
            glm::dvec3 p = a + (b - a) * ((plane - a[A]) / (b[A] - a[A]));
            p[A] = plane;
            below.add(p);
            above.add(p);
        }
    }
    return true;
}

bool cut(const Polygon& polygon, int axis, double plane, Polygon& below, Polygon& above) {
    return axis == 0   ? cut_on<0>(polygon, plane, below, above)
           : axis == 1 ? cut_on<1>(polygon, plane, below, above)
                       : cut_on<2>(polygon, plane, below, above);
}

/// The next float towards -infinity from a finite `x`: std::nextafter without its call and
/// branches (the rounding direction is a coin toss, so branches were mispredicted half the time).
float next_down(float x) {
    // As integers, floats below zero grow away from zero; +0 steps like -0, to -denorm_min.
    const auto bits = std::bit_cast<std::int32_t>(x);
    const std::int32_t from = bits == 0 ? std::numeric_limits<std::int32_t>::min() : bits;
    return std::bit_cast<float>(from > 0 ? from - 1 : from + 1);
}

/// Rounds outwards to float (the double box stays inside) and pads like conservative_bounds.
Aabb widen(const Box& box, float pad) {
    Aabb out;
    for (int axis = 0; axis < 3; ++axis) {
        const float lo = float(box.lo[axis]), hi = float(box.hi[axis]);
        const float down = next_down(lo), up = -next_down(-hi);
        out.lo[axis] = (double(lo) > box.lo[axis] ? down : lo) - pad;
        out.hi[axis] = (double(hi) < box.hi[axis] ? up : hi) + pad;
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
        return split(conservative_padding(corners_bounds(tri)), polygon, out);
    }

  private:
    /// `piece` is the part of the triangle inside the cuts so far; it gets out.size() pieces.
    std::size_t split(float pad, const Polygon& piece, std::span<Aabb> out) const {
        const Box& box = piece.box;
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
        const Box &left = below.box, &right = above.box;
        const double left_area = left.surface_area(), total = left_area + right.surface_area();
        const double share = total > 0.0 ? left_area / total : 0.5;
        const std::size_t pieces = out.size();
        // share * pieces rounded half up (std::lround for x >= 0; x - floor(x) is exact).
        const double x = share * double(pieces), whole = std::floor(x);
        const std::size_t left_pieces = std::clamp(
            std::size_t(x - whole >= 0.5 ? whole + 1 : whole), std::size_t(1), pieces - 1);
        const std::size_t made = split(pad, below, out.first(left_pieces));
        // The right half's pieces follow the left half's without a gap.
        return made + split(pad, above, out.subspan(made, pieces - left_pieces));
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
        // Exact, a sum of integers below 2^53, so in any order: four at a time in AVX (the
        // bisection's passes were most of a plan's time). min(cap, x) is std::min(x, cap).
        const __m256d scale4 = _mm256_set1_pd(scale), cap4 = _mm256_set1_pd(kMaxPieces - 1);
        __m256d sum4 = _mm256_setzero_pd();
        const std::size_t n = areas.size(), whole = n - n % 4;
        for (std::size_t i = 0; i < whole; i += 4) {
            const __m256d area = _mm256_cvtps_pd(_mm_loadu_ps(areas.data() + i));
            sum4 = _mm256_add_pd(sum4,
                                 _mm256_min_pd(cap4, _mm256_floor_pd(_mm256_mul_pd(scale4, area))));
        }
        alignas(32) std::array<double, 4> lanes;
        _mm256_store_pd(lanes.data(), sum4);
        double sum = (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
        for (std::size_t i = whole; i < n; ++i) sum += extra(scale, areas[i]);
        return sum;
    };
    // The sum is a step function of the scale; every scale on its last step within the budget
    // gives the same pieces. Bracket: total(budget / sum of areas) <= budget, as floor(x) <= x;
    // at (budget + 1) / largest, the largest box alone gets more.
    double area_sum = 0.0;
    for (const float area : areas) area_sum += double(area);
    const double largest = *std::max_element(areas.begin(), areas.end());
    double lo = double(budget) / area_sum, hi = double(budget + 1) / largest;
    // At scale 1 / min_area a box of min_area gets its first extra piece.
    if (1.0 / min_area < hi && total(1.0 / min_area) <= double(budget))
        lo = 1.0 / min_area;
    else
        for (double at_lo = total(lo); at_lo < double(budget) && hi - lo > 0x1p-40 * hi;) {
            const double mid = 0.5 * (lo + hi), at_mid = total(mid);
            if (at_mid <= double(budget))
                lo = mid, at_lo = at_mid;
            else
                hi = mid;
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
    // Four blocks at a time, each in its own sum, as one sum waits on each addition.
    constexpr std::size_t kBlock = 4096, kBlocks = 4;
    double total = 0.0;
    std::size_t begin = 0;
    for (; begin + kBlocks * kBlock <= count; begin += kBlocks * kBlock) {
        std::array<double, kBlocks> block{};
        for (std::size_t i = begin; i < begin + kBlock; ++i)
            for (std::size_t b = 0; b < kBlocks; ++b) block[b] += double(areas[i + b * kBlock]);
        for (const double sum : block) total += sum;
    }
    for (; begin < count; begin += kBlock) {
        double block = 0.0;
        for (std::size_t i = begin; i < std::min(count, begin + kBlock); ++i)
            block += double(areas[i]);
        total += block;
    }
    const double min_area = kMinSplitArea * total / double(count);
    // The triangles that may be cut: counted, then written (push_back in the loop kept its
    // counters in memory).
    const auto may_cut = [&](float area) { return area >= min_area && area > 0.0f; };
    const auto large_count = std::size_t(std::count_if(areas.begin(), areas.end(), may_cut));
    std::vector<std::uint32_t> large(large_count);
    std::vector<float> large_areas(large_count);
    for (std::size_t i = 0, k = 0; i < count; ++i)
        if (may_cut(areas[i])) {
            large[k] = std::uint32_t(i);
            large_areas[k++] = areas[i];
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
