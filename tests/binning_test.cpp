// fill_bins (geometry/binning.h) against the plain loop it replaced: the same boxes and counts,
// to the bit, for any K, any item count (odd, below and above the parallel size) and boxes of
// any scale.
#include "geometry/binning.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace edacrt {
namespace {

std::vector<Bin> reference_bins(const std::vector<Aabb>& boxes, const std::vector<int>& bin_of,
                                int k) {
    std::vector<Bin> bins(static_cast<std::size_t>(k));
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        Bin& b = bins[std::size_t(bin_of[i])];
        b.box.extend(boxes[i]);
        ++b.count;
    }
    return bins;
}

TEST(Binning, FillBinsMatchesThePlainLoopExactly) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_real_distribution<float> exponent(-30.0f, 30.0f);
    for (const int k : {2, 3, 8, 17, 256})
        for (const std::size_t count : {0, 1, 2, 7, 33, 1000, 20001}) {
            std::vector<Aabb> boxes(count);
            std::vector<int> bin_of(count);
            for (std::size_t i = 0; i < count; ++i) {
                const float scale = std::exp2(exponent(random));
                glm::vec3 a{unit(random), unit(random), unit(random)};
                glm::vec3 b{unit(random), unit(random), unit(random)};
                boxes[i].extend(a * scale);
                boxes[i].extend(b * scale);
                // Runs of one bin as well as scattered bins.
                bin_of[i] = i % 5 == 0 ? 0 : int(random() % unsigned(k));
            }
            std::vector<Bin> bins(static_cast<std::size_t>(k));
            fill_bins(
                bins, 0, count, [&](std::size_t i) { return bin_of[i]; },
                [&](std::size_t i) -> const Aabb& { return boxes[i]; }, 4096);
            const std::vector<Bin> expected = reference_bins(boxes, bin_of, k);
            for (int b = 0; b < k; ++b) {
                const Bin& got = bins[std::size_t(b)];
                const Bin& want = expected[std::size_t(b)];
                ASSERT_EQ(got.count, want.count) << "K " << k << ", " << count << " items";
                for (int a = 0; a < 3; ++a) {
                    ASSERT_EQ(got.box.lo[a], want.box.lo[a]) << "K " << k << ", bin " << b;
                    ASSERT_EQ(got.box.hi[a], want.box.hi[a]) << "K " << k << ", bin " << b;
                }
            }
        }
}

}  // namespace
}  // namespace edacrt
