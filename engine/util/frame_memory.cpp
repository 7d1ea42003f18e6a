#include "util/frame_memory.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace edacrt {
namespace {

constexpr std::size_t kHugePage = std::size_t(1) << 21;
constexpr std::size_t kMaxCachedBytes = std::size_t(1) << 30;
constexpr std::size_t kMaxCachedBlocks = 32;

/// Large blocks stay mapped after they are freed, for the next frame's arrays of about the same
/// size: a fresh tracer per frame (edacrt bench) or a renderer's next pass would otherwise fault
/// in, and have the kernel zero, every page again. On a virtual machine that returns freed 2 MiB
/// blocks to its host, those faults cost as much as a third of a frame (Conference's shadow
/// rays: 12 of 19 ms of per-frame preparation). General-purpose allocators keep such blocks for
/// the same reason; ours are few and large, so a short list does.
class LargeBlocks {
  public:
    /// A cached block of `bytes` to 2 `bytes` bytes, or null.
    void* take(std::size_t bytes) {
        std::lock_guard lock(mutex_);
        auto best = cached_.end();
        for (auto it = cached_.begin(); it != cached_.end(); ++it)
            if (it->second >= bytes && it->second / 2 <= bytes &&
                (best == cached_.end() || it->second < best->second))
                best = it;
        if (best == cached_.end()) return nullptr;
        void* p = best->first;
        cached_bytes_ -= best->second;
        live_.emplace(p, best->second);
        cached_.erase(best);
        return p;
    }

    void add(void* p, std::size_t bytes) {
        std::lock_guard lock(mutex_);
        live_.emplace(p, bytes);
    }

    /// False when `p` is not a large block. The oldest cached blocks go back to the system
    /// beyond kMaxCachedBytes or kMaxCachedBlocks.
    bool release(void* p) {
        std::lock_guard lock(mutex_);
        const auto it = live_.find(p);
        if (it == live_.end()) return false;
        cached_.emplace_back(p, it->second);
        cached_bytes_ += it->second;
        live_.erase(it);
        while (cached_bytes_ > kMaxCachedBytes || cached_.size() > kMaxCachedBlocks) {
            cached_bytes_ -= cached_.front().second;
            std::free(cached_.front().first);
            cached_.erase(cached_.begin());
        }
        return true;
    }

    /// Returns every cached block to the system (before an allocation that failed is retried).
    /// False when none was cached.
    bool clear() {
        std::lock_guard lock(mutex_);
        for (const auto& [p, bytes] : cached_) std::free(p);
        const bool had = !cached_.empty();
        cached_.clear();
        cached_bytes_ = 0;
        return had;
    }

  private:
    std::mutex mutex_;
    std::unordered_map<void*, std::size_t> live_;        // allocated large blocks and their sizes
    std::vector<std::pair<void*, std::size_t>> cached_;  // freed ones, oldest first
    std::size_t cached_bytes_ = 0;
};

LargeBlocks& large_blocks() {
    static LargeBlocks* blocks = new LargeBlocks;  // never destroyed: frees may come at exit
    return *blocks;
}

}  // namespace

void* allocate_frame_memory(std::size_t bytes, std::size_t align) {
    const bool huge = bytes >= 2 * kHugePage;
    align = std::max({align, huge ? kHugePage : 64, sizeof(void*)});
    const std::size_t rounded = (std::max<std::size_t>(bytes, 1) + align - 1) / align * align;
    if (rounded < bytes) throw std::bad_alloc();
    if (!huge) {
        void* p = std::aligned_alloc(align, rounded);
        if (!p) throw std::bad_alloc();
        return p;
    }
    LargeBlocks& blocks = large_blocks();
    if (align == kHugePage)
        if (void* p = blocks.take(rounded)) return p;
    void* p = std::aligned_alloc(align, rounded);
    if (!p && blocks.clear()) p = std::aligned_alloc(align, rounded);
    if (!p) throw std::bad_alloc();
    madvise(p, rounded, MADV_HUGEPAGE);  // advice: failure changes nothing
    blocks.add(p, rounded);
    return p;
}

void free_frame_memory(void* p) noexcept {
    // Large blocks are aligned to kHugePage: only those can be in the list.
    if (p && reinterpret_cast<std::uintptr_t>(p) % kHugePage == 0 && large_blocks().release(p))
        return;
    std::free(p);
}

}  // namespace edacrt
