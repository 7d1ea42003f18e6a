#pragma once
// Low-discrepancy samples that depend only on (seed, pixel, sample index, dimension): the
// shuffled, Owen-scrambled Sobol' (0,2)-sequence of Burley, "Practical Hash-based Owen
// Scrambling" (JCGT 2020). Every pair of dimensions is an independently scrambled 2D Sobol'
// sequence, so any prefix of a pixel's samples is stratified and renders are reproducible for
// any thread count.
#include <array>
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

/// The second Sobol' dimension's direction numbers, v_0 = 2^31 and v_k = v_{k-1} ^ (v_{k-1} >> 1)
/// (the Pascal matrix), bit-reversed and XOR-summed per byte: kPascal[j][b] is the reversed sum of
/// v_k over the set bits k of byte b placed at bits 24 - 8j .. 31 - 8j of the index. So
/// reversed(y) is four table reads of the reversed index's bytes, where summing over the index's
/// bits was a loop of up to 32 unpredictable branches (a tenth of a path-traced frame).
constexpr auto make_pascal_tables() {
    std::array<std::array<std::uint32_t, 256>, 4> tables{};
    std::uint32_t v[32];
    v[0] = 0x80000000u;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int j = 0; j < 4; ++j)
        for (std::uint32_t b = 0; b < 256; ++b) {
            std::uint32_t y = 0;
            // Bit i of byte j of the reversed index is bit 31 - (8j + i) of the index.
            for (int i = 0; i < 8; ++i)
                if ((b >> i) & 1u) y ^= v[31 - (8 * j + i)];
            tables[std::size_t(j)][b] = reverse_bits(y);
        }
    return tables;
}
inline constexpr auto kPascal = make_pascal_tables();

/// The first two Sobol' dimensions of the scrambled index whose bit reversal is `reversed`:
/// van der Corput (the index reversed) and the Pascal-matrix dimension, each returned
/// bit-reversed, as the Owen scramble that follows takes them.
constexpr void sobol_2d_reversed(std::uint32_t reversed, std::uint32_t& x_reversed,
                                 std::uint32_t& y_reversed) {
    x_reversed = reverse_bits(reversed);
    y_reversed = kPascal[0][reversed & 0xffu] ^ kPascal[1][(reversed >> 8) & 0xffu] ^
                 kPascal[2][(reversed >> 16) & 0xffu] ^ kPascal[3][reversed >> 24];
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
/// seed, the pixel and the dimension pair). Each coordinate is Owen-scrambled,
/// reverse(laine_karras(reverse(c))), of the shuffled index's Sobol' point: the shuffle
/// reverse(laine_karras(reverse(index))) is kept reversed, as both coordinates start from it,
/// and no value is reversed twice.
constexpr glm::vec2 sobol_sample_2d(std::uint32_t index, std::uint32_t stream) {
    using namespace sobol_detail;
    std::uint32_t x = 0, y = 0;
    sobol_2d_reversed(laine_karras(reverse_bits(index), stream), x, y);
    x = reverse_bits(laine_karras(x, hash_combine(stream, 0xa511e9b3u)));
    y = reverse_bits(laine_karras(y, hash_combine(stream, 0x63d83595u)));
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
