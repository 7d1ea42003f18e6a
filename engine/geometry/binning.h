#pragma once
// Binning of centroids (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies",
// 2007), shared by the divide-and-conquer tracers and the BVH: K equal bins along one axis, each
// with the bounds and the number of the items whose centroid falls in it, and the sweep that
// gives, for every candidate split j (bins 0..j left), both sides' bounds and counts. K is a
// run-time value and the caller owns the storage, so a recursion allocates nothing per node.
#include <immintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
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

/// The most bins a BinAxis may have (both tracers' K is at most this).
inline constexpr int kMaxBins = 256;

namespace binning_detail {

static_assert(sizeof(Aabb) == 24, "lo and hi are six packed floats");

/// A box in one register, lanes lo.x lo.y lo.z . . -hi.x -hi.y -hi.z (lanes 3 and 4 unused):
/// the union of two boxes is one min, max(hi) = -min(-hi) exactly.
inline __m256 box_lanes(const Aabb& b) {
    const __m128 low = _mm_loadu_ps(&b.lo.x);   // lo.x lo.y lo.z hi.x
    const __m128 high = _mm_loadu_ps(&b.lo.z);  // lo.z hi.x hi.y hi.z
    return _mm256_xor_ps(_mm256_set_m128(high, low),
                         _mm256_setr_ps(0.0f, 0.0f, 0.0f, 0.0f, 0.0f, -0.0f, -0.0f, -0.0f));
}

/// Bins items [begin, end) into `into` (K boxes as box_lanes and counts, already reset). Two
/// sets of bins take alternate items, so a run of items in one bin is two dependency chains
/// through memory instead of one; min and counts are exact, so merging them gives the bins
/// one set would.
template <typename BinOf, typename BoxOf>
void add_items(std::span<Bin> into, std::size_t begin, std::size_t end, const BinOf& bin_of,
               const BoxOf& box_of) {
    const std::size_t k = into.size();
    alignas(32) __m256 box[2][kMaxBins];
    std::uint32_t count[2][kMaxBins];
    for (std::size_t b = 0; b < k; ++b) {
        box[0][b] = box[1][b] = _mm256_set1_ps(kInfinity);
        count[0][b] = count[1][b] = 0;
    }
    const auto add = [&](int set, std::size_t i) {
        const auto b = std::size_t(bin_of(i));
        box[set][b] = _mm256_min_ps(box[set][b], box_lanes(box_of(i)));
        ++count[set][b];
    };
    std::size_t i = begin;
    for (; i + 1 < end; i += 2) {
        add(0, i);
        add(1, i + 1);
    }
    if (i < end) add(0, i);
    for (std::size_t b = 0; b < k; ++b) {
        alignas(32) float lanes[8];
        _mm256_store_ps(lanes, _mm256_min_ps(box[0][b], box[1][b]));
        Bin set;
        set.box.lo = {lanes[0], lanes[1], lanes[2]};
        set.box.hi = {-lanes[5], -lanes[6], -lanes[7]};
        set.count = count[0][b] + count[1][b];
        if (set.count > 0) into[b].merge(set);
    }
}

}  // namespace binning_detail

/// Bins items [begin, end): bin_of(i) is item i's bin, box_of(i) its bounds (a const Aabb&).
/// `bins` is reset first. Ranges of at least `parallel_items` are binned in parallel; min, max
/// and counts are exact, so the bins are the same for any thread count and any grouping.
template <typename BinOf, typename BoxOf>
void fill_bins(std::span<Bin> bins, std::size_t begin, std::size_t end, const BinOf& bin_of,
               const BoxOf& box_of, std::size_t parallel_items = 8192) {
    assert(bins.size() <= std::size_t(kMaxBins));
    std::fill(bins.begin(), bins.end(), Bin{});
    if (end - begin < parallel_items) {
        binning_detail::add_items(bins, begin, end, bin_of, box_of);
        return;
    }
    const std::vector<Bin> empty(bins.size());
    const std::vector<Bin> sum = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(begin, end, parallel_items / 2), empty,
        [&](const tbb::blocked_range<std::size_t>& range, std::vector<Bin> part) {
            binning_detail::add_items(part, range.begin(), range.end(), bin_of, box_of);
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
