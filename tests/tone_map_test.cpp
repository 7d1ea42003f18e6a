// Tone mapping and 8-bit output of extreme values: huge finite radiance is white for every
// operator (ACES overflowed to black from about 1e19), +inf white, NaN and negatives black;
// exposures that are not finite numbers of stops are rejected.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "render/film.h"
#include "render/image.h"
#include "util/error.h"

namespace edacrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kMax = std::numeric_limits<float>::max();

Image row(std::initializer_list<float> values) {
    Image image(int(values.size()), 1);
    int x = 0;
    for (float v : values) image.at(x++, 0) = glm::vec3(v);
    return image;
}

TEST(ToneMap, ExtremeValuesAreWhiteOrBlackForEveryOperator) {
    const Image linear = row({1e6f, 1e19f, 1e30f, kMax, kInf, 0.0f, -1.0f, -kInf, NAN});
    const float expected[] = {1, 1, 1, 1, 1, 0, 0, 0, 0};
    for (ToneMap op : {ToneMap::clamp, ToneMap::reinhard, ToneMap::aces}) {
        const Image shown = tone_map(linear, 0.0f, op);
        for (int x = 0; x < linear.width; ++x)
            EXPECT_NEAR(shown.at(x, 0).x, expected[x], 2e-6f)
                << "operator " << int(op) << ", radiance " << linear.at(x, 0).x;
    }
}

TEST(ToneMap, ExposureThatOverflowsIsWhite) {
    // 2^64 * 1e30 is beyond float: +inf after scaling, shown white.
    for (ToneMap op : {ToneMap::clamp, ToneMap::reinhard, ToneMap::aces})
        EXPECT_NEAR(tone_map(row({1e30f}), 64.0f, op).at(0, 0).x, 1.0f, 2e-6f) << int(op);
    EXPECT_EQ(tone_map(row({1.0f}), -64.0f, ToneMap::clamp).at(0, 0).x, std::exp2(-64.0f));
}

TEST(ToneMap, InvalidExposureIsRejected) {
    for (float ev : {NAN, kInf, -kInf, 64.5f, -1e9f}) {
        EXPECT_THROW(validate_exposure(ev), InputError) << ev;
        EXPECT_THROW(tone_map(row({1.0f}), ev, ToneMap::clamp), InputError) << ev;
    }
    EXPECT_NO_THROW(validate_exposure(-64.0f));
    EXPECT_NO_THROW(validate_exposure(64.0f));
}

TEST(ToneMap, PngOfExtremeValuesIsWhiteOrBlack) {
    // write_png clamps without tone mapping: NaN must not become an arbitrary byte.
    const auto path = std::filesystem::temp_directory_path() /
                      ("edacrt_tone_" + std::to_string(::getpid()) + ".png");
    write_png(path, row({kInf, 1e30f, NAN, -kInf, 0.5f}));
    const Image back = read_png(path);
    std::filesystem::remove(path);
    const float expected[] = {1, 1, 0, 0, 0.5f};
    for (int x = 0; x < back.width; ++x)
        EXPECT_NEAR(back.at(x, 0).x, expected[x], 0.01f) << "pixel " << x;
}

}  // namespace
}  // namespace edacrt
