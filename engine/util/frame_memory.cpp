#include "util/frame_memory.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdlib>

namespace edacrt {

void* allocate_frame_memory(std::size_t bytes, std::size_t align) {
    constexpr std::size_t kHugePage = std::size_t(1) << 21;
    const bool huge = bytes >= 2 * kHugePage;
    align = std::max({align, huge ? kHugePage : 64, sizeof(void*)});
    const std::size_t rounded = (std::max<std::size_t>(bytes, 1) + align - 1) / align * align;
    if (rounded < bytes) throw std::bad_alloc();
    void* p = std::aligned_alloc(align, rounded);
    if (!p) throw std::bad_alloc();
    if (huge) madvise(p, rounded, MADV_HUGEPAGE);  // advice: failure changes nothing
    return p;
}

void free_frame_memory(void* p) noexcept { std::free(p); }

}  // namespace edacrt
