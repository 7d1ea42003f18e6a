#include "trace/bvh_build.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "geometry/binning.h"
#include "util/error.h"
#include "util/exact_text.h"

namespace edacrt {
namespace {

constexpr std::uint32_t kParallelSubtree = 4096;  // references; smaller subtrees run serially
constexpr int kMedianDepth = kBvhMaxDepth - 16;   // from here on, halve: 2^16 refs still fit

/// A split of a node's references [first, first + count): those with bin <= last_left go left.
struct Split {
    BinAxis axis;
    int last_left = 0;
    Aabb left, right;
    std::uint32_t left_count = 0;
};

/// Builds into a node array with a slot for every possible node: a subtree over n references
/// has at most 2n - 1 nodes, so each node's descendants get a block of 2n - 2 slots fixed by
/// the split alone. Parallel subtrees then write disjoint slots and disjoint reference ranges,
/// and the tree is the same for any thread count; compact() drops the unused slots.
class Builder {
  public:
    Builder(std::span<const BvhReference> references, const BvhBuildOptions& options)
        : options_(options),
          references_(references.begin(), references.end()),
          slots_(2 * references.size() - 1) {}

    Bvh build() {
        Aabb box;
        for (const BvhReference& reference : references_) box.extend(reference.box);
        build(0, 1, 0, std::uint32_t(references_.size()), box, 0);
        Bvh bvh;
        bvh.nodes.reserve(slots_.size());
        bvh.nodes.push_back(slots_[0]);
        compact(0, 0, bvh.nodes);
        bvh.prims.resize(references_.size());
        for (std::size_t i = 0; i < references_.size(); ++i) bvh.prims[i] = references_[i].prim;
        return bvh;
    }

  private:
    /// Node `slot` over references_[first, first + count), its descendants in slots [block, block +
    /// 2 count - 2).
    void build(std::uint32_t slot, std::uint32_t block, std::uint32_t first, std::uint32_t count,
               const Aabb& box, int depth) {
        slots_[slot] = {box, first, count};
        if (count <= 1 || depth >= kBvhMaxDepth - 1) return;
        Split split;
        const bool sah = depth < kMedianDepth && sah_split(first, count, box, split);
        if (sah && split.left_count == 0) return;  // the SAH prefers a leaf
        if (!sah) {
            if (count <= options_.max_leaf) return;
            median_split(first, count, split);
        }
        const std::uint32_t left_count = split.left_count, right_count = count - left_count;
        assert(left_count > 0 && right_count > 0);
        slots_[slot].first = block;
        slots_[slot].count = 0;
        const auto left = [&] {
            build(block, block + 2, first, left_count, split.left, depth + 1);
        };
        const auto right = [&] {
            build(block + 1, block + 2 * left_count, first + left_count, right_count, split.right,
                  depth + 1);
        };
        if (count >= kParallelSubtree) {
            tbb::parallel_invoke(left, right);
        } else {
            left();
            right();
        }
    }

    /// The least-cost binned split over all three axes, partitioned; left_count = 0 when a node
    /// of at most max_leaf references is cheaper as a leaf. False when no split has a finite
    /// cost (all centroids in one point, or areas that overflow).
    bool sah_split(std::uint32_t first, std::uint32_t count, const Aabb& box, Split& best) {
        Aabb centroid_box;
        for (std::uint32_t i = first; i < first + count; ++i)
            centroid_box.extend(references_[i].box.center());
        // Per thread, not per node: resetting bins of every node's frame dominated the build.
        thread_local std::vector<Bin> bins;
        thread_local std::vector<BinSplit> candidates;
        bins.resize(std::size_t(options_.bins));
        candidates.resize(std::size_t(options_.bins - 1));
        // Cost times the node's area: C_T A + C_I (A_L N_L + A_R N_R), no division by A = 0.
        const float area = box.surface_area();
        float best_cost = kInfinity;
        for (int a = 0; a < 3; ++a) {
            BinAxis axis;
            if (!BinAxis::make(a, centroid_box.lo[a], centroid_box.hi[a], options_.bins, axis))
                continue;
            fill_bins(
                bins, first, first + count,
                [&](std::size_t i) { return axis(references_[i].box.center()); },
                [&](std::size_t i) -> const Aabb& { return references_[i].box; });
            sweep_bins(bins, candidates);
            for (int j = 0; j < options_.bins - 1; ++j) {
                const BinSplit& c = candidates[j];
                if (c.left_count == 0 || c.right_count == 0) continue;
                const float cost =
                    options_.traversal_cost * area +
                    options_.intersection_cost * (c.left.surface_area() * float(c.left_count) +
                                                  c.right.surface_area() * float(c.right_count));
                if (cost < best_cost) {
                    best_cost = cost;
                    best = {axis, j, c.left, c.right, std::uint32_t(c.left_count)};
                }
            }
        }
        if (!(best_cost < kInfinity)) return false;
        if (count <= options_.max_leaf &&
            options_.intersection_cost * float(count) * area <= best_cost) {
            best.left_count = 0;
            return true;
        }
        BvhReference* begin = references_.data() + first;
        [[maybe_unused]] const BvhReference* middle = std::partition(
            begin, begin + count,
            [&](const BvhReference& r) { return best.axis(r.box.center()) <= best.last_left; });
        assert(std::uint32_t(middle - begin) == best.left_count);
        return true;
    }

    /// Halves the references at the median centroid on the centroids' longest axis (ties by
    /// triangle number).
    void median_split(std::uint32_t first, std::uint32_t count, Split& split) {
        Aabb centroid_box;
        for (std::uint32_t i = first; i < first + count; ++i)
            centroid_box.extend(references_[i].box.center());
        const int axis = centroid_box.longest_axis();
        BvhReference* begin = references_.data() + first;
        split.left_count = count / 2;
        std::nth_element(begin, begin + split.left_count, begin + count,
                         [axis](const BvhReference& a, const BvhReference& b) {
                             const float ca = a.box.center()[axis], cb = b.box.center()[axis];
                             return ca < cb || (!(cb < ca) && a.prim < b.prim);
                         });
        split.left = split.right = Aabb{};
        for (std::uint32_t i = 0; i < count; ++i)
            (i < split.left_count ? split.left : split.right).extend(begin[i].box);
    }

    /// Copies the subtree of slot `from`, already at nodes[to], depth first.
    void compact(std::uint32_t from, std::uint32_t to, std::vector<BvhNode>& nodes) const {
        const BvhNode& node = slots_[from];
        if (node.count > 0) return;
        const std::uint32_t children = std::uint32_t(nodes.size());
        nodes[to].first = children;
        nodes.push_back(slots_[node.first]);
        nodes.push_back(slots_[node.first + 1]);
        compact(node.first, children, nodes);
        compact(node.first + 1, children + 1, nodes);
    }

    BvhBuildOptions options_;
    std::vector<BvhReference> references_;  // partitioned in place: grouped by node
    std::vector<BvhNode> slots_;
};

}  // namespace

void set_bvh_option(BvhBuildOptions& options, std::string_view key, std::string_view text) {
    const std::optional<double> number = parse_number(text);
    const double value = number.value_or(0.0);
    const auto require = [&](bool ok, const char* range) {
        if (!number || !ok)
            throw InputError("bvh option " + std::string(key) + ": '" + std::string(text) +
                             "' must be " + range);
    };
    if (key == "bins") {
        require(value == std::floor(value) && value >= 2 && value <= 256, "an integer in [2, 256]");
        options.bins = int(value);
    } else if (key == "max-leaf") {
        require(value == std::floor(value) && value >= 1 && value <= 1024,
                "an integer in [1, 1024]");
        options.max_leaf = std::uint32_t(value);
    } else if (key == "c-t") {
        require(value > 0.0 && value <= 1e6, "in (0, 1e6]");
        options.traversal_cost = float(value);
    } else {
        throw InputError("unknown bvh option '" + std::string(key) + "' (bins, max-leaf, c-t)");
    }
}

Bvh build_bvh(std::span<const BvhReference> references, const BvhBuildOptions& options) {
    assert(options.bins >= 2 && options.max_leaf >= 1);
    if (references.empty()) return {};
    return Builder(references, options).build();
}

}  // namespace edacrt
