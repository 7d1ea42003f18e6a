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

float aces(float x) {
    // Narkowicz 2015, "ACES Filmic Tone Mapping Curve".
    return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

}  // namespace

Image tone_map(const Image& linear, float exposure_ev, ToneMap op) {
    Image out = linear;
    const float scale = std::exp2(exposure_ev);
    for (glm::vec3& p : out.pixels)
        for (int c = 0; c < 3; ++c) {
            const float x = std::max(p[c] * scale, 0.0f);
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
    return out;
}

ToneMap parse_tone_map(std::string_view name) {
    if (name == "clamp") return ToneMap::clamp;
    if (name == "reinhard") return ToneMap::reinhard;
    if (name == "aces") return ToneMap::aces;
    throw InputError("unknown tone map '" + std::string(name) + "' (known: clamp, reinhard, aces)");
}

}  // namespace edacrt
