#include "render/film.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "util/error.h"

namespace edacrt {

Film::Film(int width, int height)
    : width_(width), height_(height), sum_(std::size_t(width) * std::size_t(height)) {}

void Film::add_pass(std::span<const glm::vec3> samples) {
    assert(samples.size() == sum_.size());
    for (std::size_t i = 0; i < sum_.size(); ++i) sum_[i] += glm::dvec3(samples[i]);
    ++passes_;
}

void Film::reset() {
    std::fill(sum_.begin(), sum_.end(), glm::dvec3(0.0));
    passes_ = 0;
}

Image Film::mean() const {
    Image image(width_, height_);
    if (passes_ == 0) return image;
    const double scale = 1.0 / double(passes_);
    for (std::size_t i = 0; i < sum_.size(); ++i) image.pixels[i] = glm::vec3(sum_[i] * scale);
    return image;
}

namespace {

// Every operator shows radiance above this as white in 8 bits (Reinhard: 1 - 1e-6), and
// clamping to it keeps x * x in the ACES fit finite (it overflowed from about 1e19 to NaN).
constexpr float kWhiteRadiance = 1e6f;

float aces(float x) {
    // Narkowicz 2015, "ACES Filmic Tone Mapping Curve".
    return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

}  // namespace

void validate_exposure(float exposure_ev) {
    if (!(std::abs(exposure_ev) <= kMaxExposure))
        throw InputError("exposure must be a finite number of stops in [-" +
                         std::to_string(int(kMaxExposure)) + ", " +
                         std::to_string(int(kMaxExposure)) + "]");
}

Image tone_map(Image image, float exposure_ev, ToneMap op) {
    validate_exposure(exposure_ev);
    const float scale = std::exp2(exposure_ev);
    for (glm::vec3& p : image.pixels)
        for (int c = 0; c < 3; ++c) {
            const float scaled = p[c] * scale;
            // NaN and negative values become black, +inf and huge values white.
            const float x = scaled > 0.0f ? std::min(scaled, kWhiteRadiance) : 0.0f;
            switch (op) {
                case ToneMap::clamp:
                    p[c] = std::min(x, 1.0f);
                    break;
                case ToneMap::reinhard:
                    p[c] = x / (1.0f + x);
                    break;
                case ToneMap::aces:
                    p[c] = aces(x);
                    break;
            }
        }
    return image;
}

}  // namespace edacrt
