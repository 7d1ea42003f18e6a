#pragma once
// Ray sampling (Nabata et al. 2013, Section 3.2): a sample of a node's rays, each tested against
// both child boxes of every candidate split, eight candidates at a time (intersect_boxes8, the
// counts kept in vector lanes). Per candidate it counts the sampled rays that hit each child box
// and those that enter each child first; the recursion (edacrt_recursion.h) turns the counts into
// the hit ratios alpha_L, alpha_R and the traversal order (Section 3.3).
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/binning.h"
#include "geometry/ray_box8.h"
#include "geometry/simd8.h"
#include "trace/ray_stream.h"
#include "util/hash_random.h"

namespace edacrt {

/// Which rays of a node's range make the sample.
struct RaySample {
    std::uint32_t count;
    bool draw;  // drawn with replacement by a generator seeded with `seed` (so a batch traces the
                // same way every time); otherwise the first `count` rays of the range
    std::uint32_t seed;

    /// The position of sample s in a range of `rays` rays.
    std::size_t offset(std::uint32_t s, std::size_t rays) const {
        return draw ? std::size_t((std::uint64_t(hash_combine(seed, s)) * rays) >> 32) : s;
    }
};

/// sample_rays' counts per candidate split j, and its working storage: sized once for K bins,
/// reused by every node.
struct SampleCounts {
    struct Counters {  // a block of eight candidates' counts
        __m256i lanes;
    };
    std::vector<std::uint32_t> left_hits, right_hits, left_first, right_first;
    std::vector<Boxes8> left_boxes, right_boxes;  // the candidates' boxes, eight at a time
    std::vector<Counters> counters;               // four per block of candidates

    void resize(int bins) {
        const auto k = std::size_t(bins), blocks = (k + 6) / 8;
        for (auto* v : {&left_hits, &right_hits, &left_first, &right_first}) v->resize(k);
        left_boxes.resize(blocks);
        right_boxes.resize(blocks);
        counters.resize(4 * blocks);
    }

    std::size_t bytes() const {
        std::size_t total = 0;
        for (const auto* v : {&left_hits, &right_hits, &left_first, &right_first})
            total += v->capacity() * sizeof(std::uint32_t);
        return total + (left_boxes.capacity() + right_boxes.capacity()) * sizeof(Boxes8) +
               counters.capacity() * sizeof(Counters);
    }
};

/// Tests the sample of the rays at stream positions [begin, begin + rays) against the child
/// boxes of `candidates` and counts into `counts`; on_sample(ray id) sees each sampled ray. A
/// ray that starts inside both boxes of a candidate enters them at the same distance; it counts
/// for the child on the side it comes from along `axis`, the split axis.
template <class OnSample>
void sample_rays(const RayStream& stream, std::size_t begin, std::size_t rays,
                 const RaySample& sample, int axis, std::span<const BinSplit> candidates,
                 SampleCounts& counts, const OnSample& on_sample) {
    using simd8::lane_mask;
    const int n = int(candidates.size()), blocks = (n + 7) / 8;
    for (int b = 0; b < blocks; ++b) {
        const BinSplit* split = &candidates[std::size_t(8 * b)];
        const int lanes = std::min(8, n - 8 * b);
        counts.left_boxes[b] = pack_boxes8(lanes, [&](int l) { return split[l].left; });
        counts.right_boxes[b] = pack_boxes8(lanes, [&](int l) { return split[l].right; });
        std::fill_n(&counts.counters[4 * b], 4, SampleCounts::Counters{_mm256_setzero_si256()});
    }
    for (std::uint32_t s = 0; s < sample.count; ++s) {
        const std::size_t i = begin + sample.offset(s, rays);
        on_sample(stream.id[i]);
        const SlabRay1x8 ray = make_slab_ray1x8(stream.slab_ray(i));
        const float t_far = stream.t_far[i];
        const __m256 left_on_tie =
            _mm256_castsi256_ps(_mm256_set1_epi32(std::signbit(stream.dir[axis][i]) ? 0 : -1));
        for (int b = 0; b < blocks; ++b) {
            __m256 left_entry, right_entry;
            const __m256 left =
                lane_mask(unsigned(intersect_boxes8(ray, counts.left_boxes[b], t_far, left_entry)));
            const __m256 right = lane_mask(
                unsigned(intersect_boxes8(ray, counts.right_boxes[b], t_far, right_entry)));
            const __m256 left_nearer = _mm256_or_ps(
                _mm256_cmp_ps(left_entry, right_entry, _CMP_LT_OQ),
                _mm256_and_ps(_mm256_cmp_ps(left_entry, right_entry, _CMP_EQ_OQ), left_on_tie));
            // left && (!right || left_nearer), right && (!left || !left_nearer)
            const __m256 left_first =
                _mm256_and_ps(left, _mm256_or_ps(_mm256_andnot_ps(right, left), left_nearer));
            const __m256 right_first = _mm256_andnot_ps(_mm256_and_ps(left, left_nearer), right);
            const __m256 masks[4] = {left, right, left_first, right_first};
            for (int k = 0; k < 4; ++k)  // a true lane is -1: subtracting counts it
                counts.counters[4 * b + k].lanes = _mm256_sub_epi32(
                    counts.counters[4 * b + k].lanes, _mm256_castps_si256(masks[k]));
        }
    }
    for (int j = 0; j < n; ++j) {
        const auto lane = [&](int k) {
            alignas(32) std::uint32_t lanes[8];
            _mm256_store_si256(reinterpret_cast<__m256i*>(lanes),
                               counts.counters[4 * (j / 8) + k].lanes);
            return lanes[j % 8];
        };
        counts.left_hits[j] = lane(0);
        counts.right_hits[j] = lane(1);
        counts.left_first[j] = lane(2);
        counts.right_first[j] = lane(3);
    }
}

}  // namespace edacrt
