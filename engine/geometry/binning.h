#pragma once
// Binning of centroids (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies",
// 2007), shared by the divide-and-conquer tracers and the BVH: K equal bins along one axis, each
// with the bounds and the number of the items whose centroid falls in it, and the sweep that
// gives, for every candidate split j (bins 0..j left), both sides' bounds and counts. K is a
// run-time value and the caller owns the storage, so a recursion allocates nothing per node.
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <span>
#include <vector>

#include "geometry/aabb.h"

namespace edacrt {

/// The bin of a centroid already mapped to bin units, x = (c - origin) * scale, clamped to
/// [0, bins - 1]. Extreme scenes make x NaN (a centroid range that overflows gives scale 0
/// against an infinite offset; one of FLT_MIN gives an infinite scale against a zero offset):
/// NaN lands in bin 0, and no NaN or out-of-range value is converted to int (undefined
/// behaviour).
inline int bin_index(float x, int bins) {
    return x >= 0.0f ? (x < float(bins) ? int(x) : bins - 1) : 0;
}

/// K equal bins over [lo, hi] on one axis.
struct BinAxis {
    int axis = 0;
    int bins = 0;
    float origin = 0.0f;
    float scale = 0.0f;  // bins per unit, shrunk by 1e-6 so that hi lands in the last bin

    /// False when the range is empty, a point or NaN: nothing to separate on this axis.
    static bool make(int axis, float lo, float hi, int bins, BinAxis& out) {
        const float width = hi - lo;
        if (!(width > 0.0f)) return false;
        out = {axis, bins, lo, float(bins) * (1.0f - 1e-6f) / width};
        return true;
    }
    int operator()(const glm::vec3& centroid) const {
        return bin_index((centroid[axis] - origin) * scale, bins);
    }
};

/// One bin: the union of its items' bounds and how many there are.
struct Bin {
    Aabb box;
    std::size_t count = 0;

    void add(const Aabb& item) {
        box.extend(item);
        ++count;
    }
    void merge(const Bin& other) {
        box.extend(other.box);
        count += other.count;
    }
};

/// Candidate split j of a sweep: bins 0..j left, j + 1..K - 1 right.
struct BinSplit {
    Aabb left, right;
    std::size_t left_count = 0, right_count = 0;
};

/// Bins items [begin, end): bin_of(i) is item i's bin, box_of(i) its bounds. `bins` is reset
/// first. Ranges of at least `parallel_items` are binned in parallel; min, max and counts are
/// exact, so the bins are the same for any thread count and any grouping.
template <typename BinOf, typename BoxOf>
void fill_bins(std::span<Bin> bins, std::size_t begin, std::size_t end, const BinOf& bin_of,
               const BoxOf& box_of, std::size_t parallel_items = 8192) {
    const auto add = [&](std::size_t from, std::size_t to, std::span<Bin> into) {
        for (std::size_t i = from; i != to; ++i) into[bin_of(i)].add(box_of(i));
    };
    std::fill(bins.begin(), bins.end(), Bin{});
    if (end - begin < parallel_items) {
        add(begin, end, bins);
        return;
    }
    const std::vector<Bin> empty(bins.size());
    const std::vector<Bin> sum = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(begin, end, parallel_items / 2), empty,
        [&](const tbb::blocked_range<std::size_t>& range, std::vector<Bin> part) {
            add(range.begin(), range.end(), part);
            return part;
        },
        [](std::vector<Bin> a, const std::vector<Bin>& b) {
            for (std::size_t k = 0; k < a.size(); ++k) a[k].merge(b[k]);
            return a;
        });
    std::copy(sum.begin(), sum.end(), bins.begin());
}

/// Sweeps the bins from both ends: splits[j] (j < K - 1) gets candidate j's two sides.
inline void sweep_bins(std::span<const Bin> bins, std::span<BinSplit> splits) {
    assert(bins.size() >= 2 && splits.size() >= bins.size() - 1);
    const std::size_t candidates = bins.size() - 1;
    Bin side;
    for (std::size_t j = 0; j < candidates; ++j) {
        side.merge(bins[j]);
        splits[j].left = side.box;
        splits[j].left_count = side.count;
    }
    side = Bin{};
    for (std::size_t j = candidates; j-- > 0;) {
        side.merge(bins[j + 1]);
        splits[j].right = side.box;
        splits[j].right_count = side.count;
    }
}

}  // namespace edacrt
