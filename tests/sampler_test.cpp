// The pixel sampler (render/sampler.h) against Burley's definition written out the slow way,
// and the property the renderer relies on: every prefix of a pixel's samples is stratified.
#include "render/sampler.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <set>

namespace edacrt {
namespace {

// Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020), Listings 1-3, bit by bit.
std::uint32_t reverse(std::uint32_t x) {
    std::uint32_t r = 0;
    for (int i = 0; i < 32; ++i) r |= ((x >> i) & 1u) << (31 - i);
    return r;
}

std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
    return reverse(sobol_detail::laine_karras(reverse(x), seed));
}

void sobol_reference(std::uint32_t index, std::uint32_t& x, std::uint32_t& y) {
    x = reverse(index);
    y = 0;
    std::uint32_t direction = 0x80000000u;
    for (int bit = 0; bit < 32; ++bit) {
        if ((index >> bit) & 1u) y ^= direction;
        direction ^= direction >> 1;
    }
}

glm::vec2 sample_reference(std::uint32_t index, std::uint32_t stream) {
    std::uint32_t x = 0, y = 0;
    sobol_reference(owen_scramble(index, stream), x, y);
    x = owen_scramble(x, hash_combine(stream, 0xa511e9b3u));
    y = owen_scramble(y, hash_combine(stream, 0x63d83595u));
    return {hash_to_unit_float(x), hash_to_unit_float(y)};
}

TEST(Sampler, MatchesTheDefinitionBitForBit) {
    std::mt19937 random(7);
    std::uniform_int_distribution<std::uint32_t> any;
    const auto check = [](std::uint32_t index, std::uint32_t stream) {
        const glm::vec2 fast = sobol_sample_2d(index, stream);
        const glm::vec2 slow = sample_reference(index, stream);
        ASSERT_EQ(fast.x, slow.x) << index << " " << stream;
        ASSERT_EQ(fast.y, slow.y) << index << " " << stream;
    };
    for (std::uint32_t stream : {0u, 1u, 0xffffffffu, 0x80000000u})
        for (std::uint32_t index = 0; index < 4096; ++index) check(index, stream);
    for (int k = 0; k < 200000; ++k) check(any(random), any(random));
    for (int bit = 0; bit < 32; ++bit) check(1u << bit, any(random));
    check(0xffffffffu, 12345u);
}

// A (0,2)-sequence: any 2^m consecutive samples from 0 put one point in each elementary box
// 2^-a x 2^-(m-a), whatever the scramble (Owen scrambling keeps the net property).
TEST(Sampler, EveryPowerOfTwoPrefixIsStratified) {
    for (std::uint32_t stream : {3u, 77u, 0xdeadbeefu}) {
        for (int m = 0; m <= 8; ++m) {
            const std::uint32_t n = 1u << m;
            for (int a = 0; a <= m; ++a) {
                std::set<std::pair<std::uint32_t, std::uint32_t>> boxes;
                for (std::uint32_t i = 0; i < n; ++i) {
                    const glm::vec2 p = sobol_sample_2d(i, stream);
                    ASSERT_GE(p.x, 0.0f);
                    ASSERT_LT(p.x, 1.0f);
                    ASSERT_GE(p.y, 0.0f);
                    ASSERT_LT(p.y, 1.0f);
                    boxes.insert({std::uint32_t(p.x * float(1u << a)),
                                  std::uint32_t(p.y * float(1u << (m - a)))});
                }
                EXPECT_EQ(boxes.size(), n) << "stream " << stream << ", 2^" << m << ", a " << a;
            }
        }
    }
}

TEST(Sampler, PixelSamplerDrawsFromItsOwnStream) {
    const PixelSampler a(1, 10, 3), b(1, 11, 3), c(2, 10, 3);
    EXPECT_NE(a.get_2d(0), b.get_2d(0));
    EXPECT_NE(a.get_2d(0), c.get_2d(0));
    EXPECT_NE(a.get_2d(0), a.get_2d(1));
    EXPECT_EQ(a.get_2d(0), PixelSampler(1, 10, 3).get_2d(0));
    // Sub-sample k of count: sample index * count + k of the same sequence.
    EXPECT_EQ(PixelSampler(1, 10, 2).get_2d(5, 3, 4), PixelSampler(1, 10, 11).get_2d(5));
}

}  // namespace
}  // namespace edacrt
