#pragma once
// Low-discrepancy samples that depend only on (seed, pixel, sample index, dimension): the
// shuffled, Owen-scrambled Sobol' (0,2)-sequence of Burley, "Practical Hash-based Owen
// Scrambling" (JCGT 2020). Every pair of dimensions is an independently scrambled 2D Sobol'
// sequence, so any prefix of a pixel's samples is stratified and renders are reproducible for
// any thread count.
#include <cstdint>
#include <glm/vec2.hpp>

#include "util/hash_random.h"

namespace edacrt {

namespace sobol_detail {

constexpr std::uint32_t reverse_bits(std::uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}

/// Laine-Karras style permutation: an Owen scramble of the bit-reversed value (Burley 2020).
constexpr std::uint32_t laine_karras(std::uint32_t x, std::uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

constexpr std::uint32_t nested_uniform_scramble(std::uint32_t x, std::uint32_t seed) {
    return reverse_bits(laine_karras(reverse_bits(x), seed));
}

/// The first two Sobol' dimensions: van der Corput, and the Pascal-matrix dimension whose
/// direction numbers are v_k = v_{k-1} ^ (v_{k-1} >> 1).
constexpr void sobol_2d(std::uint32_t index, std::uint32_t& x, std::uint32_t& y) {
    x = reverse_bits(index);
    y = 0;
    std::uint32_t direction = 0x80000000u;
    for (; index != 0; index >>= 1) {
        if (index & 1u) y ^= direction;
        direction ^= direction >> 1;
    }
}

}  // namespace sobol_detail

/// The time of the pass that starts at sample `sample` in a shutter of `shutter` seconds
/// centred on `time` (motion blur: passes at several times average in the film). The base-2
/// radical inverse of the sample index, shifted by a half, so that sample 0 is at `time` and
/// passes of one sample each stratify the shutter.
constexpr double shutter_time(double time, double shutter, std::uint32_t sample) {
    double u = double(sobol_detail::reverse_bits(sample)) * 0x1p-32 + 0.5;
    if (u >= 1.0) u -= 1.0;
    return time + shutter * (u - 0.5);
}

/// A point in [0,1)^2: sample `index` of the 2D sequence identified by `stream` (a hash of the
/// seed, the pixel and the dimension pair).
constexpr glm::vec2 sobol_sample_2d(std::uint32_t index, std::uint32_t stream) {
    using namespace sobol_detail;
    std::uint32_t x = 0, y = 0;
    sobol_2d(nested_uniform_scramble(index, stream), x, y);
    x = nested_uniform_scramble(x, hash_combine(stream, 0xa511e9b3u));
    y = nested_uniform_scramble(y, hash_combine(stream, 0x63d83595u));
    return {hash_to_unit_float(x), hash_to_unit_float(y)};
}

/// The samples of one pixel in one pass: dimension pair `d` of sample `index`.
class PixelSampler {
  public:
    constexpr PixelSampler(std::uint32_t seed, std::uint32_t pixel, std::uint32_t index)
        : base_(hash_combine(seed, pixel)), index_(index) {}

    constexpr glm::vec2 get_2d(std::uint32_t pair) const {
        return sobol_sample_2d(index_, hash_combine(base_, pair));
    }
    /// Sub-sample `k` of `count` of a pair (several rays per hit, e.g. ambient occlusion):
    /// consecutive indices of the same sequence, so they are stratified too.
    constexpr glm::vec2 get_2d(std::uint32_t pair, std::uint32_t k, std::uint32_t count) const {
        return sobol_sample_2d(index_ * count + k, hash_combine(base_, pair));
    }

  private:
    std::uint32_t base_;
    std::uint32_t index_;
};

}  // namespace edacrt
