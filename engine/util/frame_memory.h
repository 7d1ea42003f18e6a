#pragma once
// Memory for per-frame arrays that a fresh tracer fills once per frame (edacrt bench makes one
// per frame; an animation refills them every frame): large blocks on 2 MiB pages where the
// kernel allows it (transparent huge pages on request), since touching tens of megabytes in
// 4 KiB pages costs a page fault per page; large blocks kept mapped when freed, for the next
// frame's arrays of about the same size (frame_memory.cpp); and elements left uninitialised by
// a resize, since the caller writes every one at once (value-initialising them first was a
// second pass).
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace edacrt {

/// `bytes` aligned to `align` (a power of two), on huge pages when large; free_frame_memory
/// releases it (a large block to the next allocation that fits it). Thread-safe. Throws
/// std::bad_alloc.
void* allocate_frame_memory(std::size_t bytes, std::size_t align);
void free_frame_memory(void* p) noexcept;

/// Allocator of FrameVector: allocate_frame_memory, and default-initialisation on resize.
template <class T>
struct FrameAllocator {
    using value_type = T;
    FrameAllocator() = default;
    template <class U>
    FrameAllocator(const FrameAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
        return static_cast<T*>(allocate_frame_memory(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, std::size_t) noexcept { free_frame_memory(p); }
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;  // default-, not value-initialised
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

template <class T, class U>
bool operator==(const FrameAllocator<T>&, const FrameAllocator<U>&) {
    return true;  // stateless: any one frees what another allocated
}

template <class T>
using FrameVector = std::vector<T, FrameAllocator<T>>;

}  // namespace edacrt
