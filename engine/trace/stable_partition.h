#pragma once
// Stable in-place partition of index arrays, in parallel for large ranges. Stable means the
// result is defined by the input alone: the same for any thread count and block schedule, so a
// recursion built on it is deterministic.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace edacrt {

/// Ranges at least this long are partitioned in parallel, in blocks of this many items
/// (about 50 us of box tests: larger than a task's overhead).
inline constexpr std::size_t kParallelItems = 8192;

/// Scratch for partition(): as many items and flags as the longest range.
struct PartitionScratch {
    std::vector<std::uint32_t> items;
    std::vector<std::uint8_t> keep;
    std::vector<std::size_t> block_kept;
    void reserve(std::size_t count) {
        items.resize(std::max(items.size(), count));
        keep.resize(std::max(keep.size(), count));
        block_kept.resize(std::max(block_kept.size(), count / kParallelItems + 2));
    }
};

/// Moves the items for which `keep(i)` holds (i: the item's position) to the front, both groups
/// keeping their order, and returns how many there are. `keep` runs once per position, from any
/// thread for large ranges.
template <class Pred>
std::size_t partition(std::uint32_t* items, std::size_t count, PartitionScratch& scratch,
                      const Pred& keep_at) {
    std::uint32_t* rejected = scratch.items.data();
    if (count < kParallelItems) {
        std::size_t kept = 0, dropped = 0;
        for (std::size_t i = 0; i < count; ++i) {
            const std::uint32_t item = items[i];
            if (keep_at(i))
                items[kept++] = item;  // kept <= i: never overwrites an unread item
            else
                rejected[dropped++] = item;
        }
        std::copy_n(rejected, dropped, items + kept);
        return kept;
    }
    // Pass 1: each block decides its items; pass 2: each block writes its kept items after
    // the earlier blocks' ones and its rejected items after all kept ones; then copy back.
    const std::size_t blocks = (count + kParallelItems - 1) / kParallelItems;
    std::uint8_t* keep = scratch.keep.data();
    std::size_t* offset = scratch.block_kept.data();
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        const std::size_t begin = b * kParallelItems, end = std::min(count, begin + kParallelItems);
        std::size_t kept = 0;
        for (std::size_t i = begin; i < end; ++i) kept += keep[i] = keep_at(i);
        offset[b + 1] = kept;
    });
    offset[0] = 0;
    for (std::size_t b = 0; b < blocks; ++b) offset[b + 1] += offset[b];
    const std::size_t total = offset[blocks];
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        const std::size_t begin = b * kParallelItems, end = std::min(count, begin + kParallelItems);
        std::size_t kept = offset[b], dropped = total + (begin - offset[b]);
        for (std::size_t i = begin; i < end; ++i) rejected[keep[i] ? kept++ : dropped++] = items[i];
    });
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        const std::size_t begin = b * kParallelItems, end = std::min(count, begin + kParallelItems);
        std::copy(rejected + begin, rejected + end, items + begin);
    });
    return total;
}

}  // namespace edacrt
