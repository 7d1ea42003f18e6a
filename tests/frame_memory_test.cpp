// FrameVector: per-frame arrays on huge pages when large, kept for the next frame when freed,
// default-initialised on resize.
#include "util/frame_memory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <new>

#include "geometry/aabb.h"

namespace edacrt {
namespace {

TEST(FrameMemory, LargeAndSmallBlocksAreAlignedAndHoldWhatIsWritten) {
    for (const std::size_t n : {std::size_t(1), std::size_t(1000), std::size_t(3) << 20}) {
        FrameVector<std::uint32_t> v(n);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % 64, 0u);
        if (n * sizeof(std::uint32_t) >= (std::size_t(4) << 20)) {
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % (std::size_t(1) << 21), 0u);
        }
        for (std::size_t i = 0; i < n; ++i) v[i] = std::uint32_t(i * 7);
        v.resize(n + 5);  // moves into a new block
        for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(v[i], std::uint32_t(i * 7));
    }
}

TEST(FrameMemory, TypesWithConstructorsAreStillConstructed) {
    FrameVector<Aabb> boxes(3);  // Aabb's default is the empty box
    for (const Aabb& box : boxes) EXPECT_TRUE(box.lo.x > box.hi.x);
    FrameVector<Aabb> filled(2, Aabb{glm::vec3(1.0f), glm::vec3(2.0f)});
    EXPECT_EQ(filled[1].hi.y, 2.0f);
}

// A large block stays mapped when freed and serves the next allocation of about its size (the
// next frame's array), not a much smaller one; what it held may still be there, and every byte
// can be written again.
TEST(FrameMemory, AFreedLargeBlockServesTheNextFrame) {
    constexpr std::size_t kBytes = std::size_t(16) << 20;
    auto* first = static_cast<unsigned char*>(allocate_frame_memory(kBytes, 64));
    std::fill_n(first, kBytes, 1);
    free_frame_memory(first);
    auto* again = static_cast<unsigned char*>(allocate_frame_memory(kBytes - 4096, 64));
    EXPECT_EQ(again, first);
    std::fill_n(again, kBytes - 4096, 2);
    auto* other = static_cast<unsigned char*>(allocate_frame_memory(kBytes, 64));
    EXPECT_NE(other, again);  // again is in use
    free_frame_memory(again);
    constexpr std::size_t kSmall = std::size_t(5) << 20;  // large too, but under half
    auto* small = static_cast<unsigned char*>(allocate_frame_memory(kSmall, 64));
    EXPECT_NE(small, again);  // would waste more than half of it
    std::fill_n(small, kSmall, 3);
    free_frame_memory(small);
    free_frame_memory(other);
    free_frame_memory(nullptr);
}

TEST(FrameMemory, AnImpossibleSizeIsBadAlloc) {
    FrameAllocator<Aabb> allocator;
    EXPECT_THROW((void)allocator.allocate(std::size_t(-1) / 8), std::bad_alloc);
    EXPECT_THROW(allocate_frame_memory(std::size_t(-1) - 10, 64), std::bad_alloc);
}

}  // namespace
}  // namespace edacrt
