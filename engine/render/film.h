#pragma once
// The progressive film: one sample per pixel is added per pass, and the image is their mean.
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "render/image.h"

namespace edacrt {

class Film {
  public:
    Film(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    int passes() const { return passes_; }

    /// Adds one pass: `samples` holds one radiance sample per pixel, row by row.
    void add_pass(std::span<const glm::vec3> samples);

    /// Forgets all passes (the camera, scene or settings changed).
    void reset();

    /// The mean of the passes so far (black before the first).
    Image mean() const;

  private:
    int width_, height_;
    int passes_ = 0;
    std::vector<glm::dvec3> sum_;  // double: exact enough over millions of passes
};

/// How linear radiance becomes display values in [0, 1] (before sRGB encoding).
enum class ToneMap { clamp, reinhard, aces };

/// Scales by 2^exposure_ev, then applies `op` per channel (aces: Narkowicz's fit).
Image tone_map(const Image& linear, float exposure_ev, ToneMap op);

ToneMap parse_tone_map(std::string_view name);

}  // namespace edacrt
