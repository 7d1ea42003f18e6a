#pragma once
// The progressive film: one sample per pixel is added per pass, and the image is their mean.
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "render/image.h"
#include "util/enum_table.h"

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
inline constexpr auto kToneMaps =
    enum_table<ToneMap>("tone map", {{ToneMap::clamp, "clamp", "values above 1 are white"},
                                     {ToneMap::reinhard, "reinhard", "x / (1 + x)"},
                                     {ToneMap::aces, "aces", "Narkowicz's ACES fit"}});

/// Exposures beyond this many stops are rejected: 2^64 already turns any visible radiance
/// white or black.
inline constexpr float kMaxExposure = 64.0f;

/// Throws InputError unless |exposure_ev| <= kMaxExposure (NaN and infinities included).
void validate_exposure(float exposure_ev);

/// Scales by 2^exposure_ev, then applies `op` per channel (aces: Narkowicz's fit). Values that
/// are not positive (NaN included) become 0; +inf and radiance from 1e6 up become white, as
/// bright as any operator shows. Throws InputError for an invalid exposure.
Image tone_map(Image linear, float exposure_ev, ToneMap op);

}  // namespace edacrt
