// An in-place partition eight rays at a time (AVX2): each block of eight is tested against the
// box, permuted so that its passing rays come first, and stored twice, at the passing end and
// at the rejected end of the range; the range is read from whichever end has less room, so
// both stores always land on rays already read (the two-ended vectorised partition of
// Bramas 2017, used by vxsort). Coherent rays move less: whole blocks already in place at
// either end stay, and a block that passes or misses whole is stored once, unpermuted. The box
// tests run a few blocks ahead of the moves. Nine arrays move together, so a node's rays stay
// contiguous.
#include "trace/ray_filter.h"

#include <immintrin.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstdint>
#include <vector>

#include "geometry/ray_box8.h"

namespace edacrt {
namespace {

constexpr int kArrays = 9;

/// For each 8-bit mask, the lanes with their bit set, in order, then the others (3 bits each
/// in one byte per output lane).
constexpr std::array<std::uint64_t, 256> make_pass_first() {
    std::array<std::uint64_t, 256> table{};
    for (unsigned mask = 0; mask < 256; ++mask) {
        int out = 0;
        for (int pass : {1, 0})
            for (unsigned lane = 0; lane < 8; ++lane)
                if (((mask >> lane) & 1) == unsigned(pass))
                    table[mask] |= std::uint64_t(lane) << (8 * out++);
    }
    return table;
}
constexpr std::array<std::uint64_t, 256> kPassFirst = make_pass_first();

struct Arrays {
    float* a[kArrays];
    explicit Arrays(const RayStream& s)
        : a{s.org[0], s.org[1], s.org[2],
            s.dir[0], s.dir[1], s.dir[2],
            s.tmin,   s.t_far,  reinterpret_cast<float*>(s.id)} {}
};

struct Block {
    __m256 v[kArrays];
};

Block load(const Arrays& s, std::size_t i) {
    Block b;
    for (int k = 0; k < kArrays; ++k) b.v[k] = _mm256_loadu_ps(s.a[k] + i);
    return b;
}

[[gnu::always_inline]] inline unsigned passes(const Block& b, const Aabb8& box) {
    const __m256 one = _mm256_set1_ps(1.0f);  // make_slab_ray's 1/dir, with its +-inf for +-0
    const SlabRay8 ray{
        {b.v[0], b.v[1], b.v[2]},
        {_mm256_div_ps(one, b.v[3]), _mm256_div_ps(one, b.v[4]), _mm256_div_ps(one, b.v[5])},
        b.v[6],
        b.v[7]};
    __m256 entry;
    return unsigned(_mm256_movemask_ps(intersect_box8(ray, box, entry)));
}

/// Rays held aside: two blocks and a middle of fewer than eight, or a short range whole.
struct Pending {
    alignas(32) float a[kArrays][24];
    /// Rays [n, end) are not rays: zeros, so that the block holding them is well defined.
    void clear(std::size_t n, std::size_t end) {
        for (int k = 0; k < kArrays; ++k) std::fill(a[k] + n, a[k] + end, 0.0f);
    }
    Block block(std::size_t i) const {
        Block b;
        for (int k = 0; k < kArrays; ++k) b.v[k] = _mm256_load_ps(a[k] + i);
        return b;
    }
};

/// The box test's verdicts on an end's next unread blocks, in the order that end reads them.
struct Lookahead {
    static constexpr int kAhead = 8;
    std::uint8_t masks[kAhead];
    int next = 0, count = 0;
    /// Tests up to kAhead blocks of the unread rays [lo, hi): upwards from lo, or downwards
    /// from hi.
    void test(const Arrays& s, const Aabb8& box, std::size_t lo, std::size_t hi, bool upwards) {
        next = count = 0;
        for (; count < kAhead && hi - lo >= 8; ++count)
            if (upwards) {
                masks[count] = std::uint8_t(passes(load(s, lo), box));
                lo += 8;
            } else {
                hi -= 8;
                masks[count] = std::uint8_t(passes(load(s, hi), box));
            }
    }
    /// The next block's verdict (testing ahead first if none is left), kept by peek, consumed
    /// by take.
    unsigned peek(const Arrays& s, const Aabb8& box, std::size_t lo, std::size_t hi, bool upwards) {
        if (next == count) test(s, box, lo, hi, upwards);
        return masks[next];
    }
    void skip() { ++next; }
    unsigned take(const Arrays& s, const Aabb8& box, std::size_t lo, std::size_t hi, bool upwards) {
        const unsigned mask = peek(s, box, lo, hi, upwards);
        skip();
        return mask;
    }
};

/// Writes the first `n` pending rays to the range's ends, passing ones (bit i of `mask`)
/// upwards from write_l, the others downwards from write_r; returns the new write_l.
std::size_t place(const Arrays& s, const Pending& p, std::size_t n, std::uint32_t mask,
                  std::size_t write_l, std::size_t write_r) {
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t to = (mask >> i) & 1 ? write_l++ : --write_r;
        for (int k = 0; k < kArrays; ++k) s.a[k][to] = p.a[k][i];
    }
    return write_l;
}

std::size_t filter_sequential(const Arrays& s, std::size_t begin, std::size_t end,
                              const Aabb& box) {
    const Aabb8 box8 = broadcast(box);
    const std::size_t start = begin;
    // Each end's next blocks are tested kAhead at a time before any of them moves: the box
    // tests then depend on no cursor and overlap, where one block at a time each store waited
    // for its own test. A block is tested while unread, so its data is still there when it
    // moves; a tested block the other end reaches first is never moved from this end.
    Lookahead left, right;
    // Whole blocks already in place stay: passing ones at the front, missed ones at the back
    // (two fifths of the rays filtered in Sponza's camera and shadow sets). Not looked for in
    // a range the short path below takes whole.
    while (end - begin >= 16 && left.peek(s, box8, begin, end, true) == 0xff) {
        left.skip();
        begin += 8;
    }
    while (end - begin >= 16 && right.peek(s, box8, begin, end, false) == 0) {
        right.skip();
        end -= 8;
    }
    Pending pending;
    if (end - begin < 16) {  // held aside whole, tested as two blocks
        const std::size_t n = end - begin;
        for (int k = 0; k < kArrays; ++k) std::copy_n(s.a[k] + begin, n, pending.a[k]);
        pending.clear(n, 16);
        const std::uint32_t mask = passes(pending.block(0), box8) | passes(pending.block(8), box8)
                                                                        << 8;
        return place(s, pending, n, mask, begin, end) - start;
    }
    // Passing rays are written upwards from write_l, rejected ones downwards from write_r.
    // The first and last blocks wait in registers, so 16 rays of room exist between the
    // cursors and the unread middle; reading from the end with less room keeps at least 8 on
    // each side, enough for a full store of either kind.
    const Block first = load(s, begin), last = load(s, end - 8);
    const std::uint32_t first_mask = left.take(s, box8, begin, end, true),
                        last_mask = right.take(s, box8, begin, end, false);
    std::size_t read_l = begin + 8, read_r = end - 8, write_l = begin, write_r = end;
    while (read_r - read_l >= 8) {
        Block b;
        unsigned mask;
        if (read_l - write_l <= write_r - read_r) {
            mask = left.take(s, box8, read_l, read_r, true);
            b = load(s, read_l);
            read_l += 8;
        } else {
            mask = right.take(s, box8, read_l, read_r, false);
            read_r -= 8;
            b = load(s, read_r);
        }
        const int passed = std::popcount(mask);
        if (mask == 0xff) {  // a whole block to one end: not permuted, stored once
            for (int k = 0; k < kArrays; ++k) _mm256_storeu_ps(s.a[k] + write_l, b.v[k]);
        } else if (mask == 0) {
            for (int k = 0; k < kArrays; ++k) _mm256_storeu_ps(s.a[k] + write_r - 8, b.v[k]);
        } else {
            const __m256i order =
                _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(std::int64_t(kPassFirst[mask])));
            for (int k = 0; k < kArrays; ++k) {
                const __m256 v = _mm256_permutevar8x32_ps(b.v[k], order);
                _mm256_storeu_ps(s.a[k] + write_l, v);
                _mm256_storeu_ps(s.a[k] + write_r - 8, v);
            }
        }
        write_l += std::size_t(passed);
        write_r -= std::size_t(8 - passed);
    }
    // The gap [write_l, write_r) now holds exactly the unread middle and room for the two
    // waiting blocks: move the middle out, then place all of them.
    const std::size_t middle = read_r - read_l;
    for (int k = 0; k < kArrays; ++k) {
        _mm256_store_ps(pending.a[k], first.v[k]);
        _mm256_store_ps(pending.a[k] + 8, last.v[k]);
        std::copy_n(s.a[k] + read_l, middle, pending.a[k] + 16);
    }
    pending.clear(16 + middle, 24);
    const std::uint32_t mask = first_mask | last_mask << 8 | passes(pending.block(16), box8) << 16;
    return place(s, pending, 16 + middle, mask, write_l, write_r) - start;
}

/// A run of misplaced rays: rejected ones before the split point, or passing ones after it.
struct Run {
    std::size_t start, count, before;  // `before`: misplaced rays in earlier runs
};

/// Where the misplaced ray numbered k lies: the run that holds it and the offset in that run.
std::pair<std::size_t, std::size_t> locate(const std::vector<Run>& runs, std::size_t k) {
    const auto run = std::upper_bound(runs.begin(), runs.end(), k,
                                      [](std::size_t x, const Run& r) { return x < r.before; }) -
                     1;
    return {std::size_t(run - runs.begin()), k - run->before};
}

/// Swaps the misplaced rays numbered [from, to) of `left` with those of `right`, a stretch of
/// consecutive positions at a time.
void swap_misplaced(const Arrays& s, const std::vector<Run>& left, const std::vector<Run>& right,
                    std::size_t from, std::size_t to) {
    auto [l, l_offset] = locate(left, from);
    auto [r, r_offset] = locate(right, from);
    for (std::size_t k = from; k < to;) {
        const std::size_t n =
            std::min({to - k, left[l].count - l_offset, right[r].count - r_offset});
        const std::size_t i = left[l].start + l_offset, j = right[r].start + r_offset;
        for (int a = 0; a < kArrays; ++a) std::swap_ranges(s.a[a] + i, s.a[a] + i + n, s.a[a] + j);
        k += n;
        l_offset += n;
        r_offset += n;
        if (l_offset == left[l].count) ++l, l_offset = 0;
        if (r_offset == right[r].count) ++r, r_offset = 0;
    }
}

}  // namespace

std::size_t filter_rays(const RayStream& stream, std::size_t begin, std::size_t count,
                        const Aabb& box) {
    const Arrays s(stream);
    if (count < 2 * kParallelFilterRays) return filter_sequential(s, begin, begin + count, box);
    // Each fixed block is partitioned on its own; then the rejected rays left of the total
    // split point swap places with the passing rays right of it, the k-th with the k-th.
    const std::size_t blocks = (count + kParallelFilterRays - 1) / kParallelFilterRays;
    std::vector<std::size_t> passed(blocks);
    const auto block_begin = [&](std::size_t b) { return begin + b * kParallelFilterRays; };
    const auto block_end = [&](std::size_t b) {
        return std::min(begin + count, block_begin(b) + kParallelFilterRays);
    };
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        passed[b] = filter_sequential(s, block_begin(b), block_end(b), box);
    });
    std::size_t total = 0;
    for (const std::size_t p : passed) total += p;
    const std::size_t split = begin + total;
    std::vector<Run> rejected_left, passed_right;
    std::size_t misplaced_left = 0, misplaced_right = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
        const std::size_t mid = block_begin(b) + passed[b];
        if (mid < split) {
            const std::size_t n = std::min(block_end(b), split) - mid;
            rejected_left.push_back({mid, n, misplaced_left});
            misplaced_left += n;
        }
        if (mid > split) {
            const std::size_t start = std::max(block_begin(b), split);
            passed_right.push_back({start, mid - start, misplaced_right});
            misplaced_right += mid - start;
        }
    }
    assert(misplaced_left == misplaced_right);
    const std::size_t chunk = kParallelFilterRays;
    tbb::parallel_for(std::size_t(0), (misplaced_left + chunk - 1) / chunk, [&](std::size_t c) {
        swap_misplaced(s, rejected_left, passed_right, c * chunk,
                       std::min(misplaced_left, (c + 1) * chunk));
    });
    return total;
}

}  // namespace edacrt
