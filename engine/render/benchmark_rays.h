#pragma once
// Random numbers and camera rays shared by the benchmarks' ray sets (bench/paper_rays.cpp,
// `edacrt bench`), so that both make the same rays for the same view, size and seed. Numbers
// are counter-based (util/hash_random.h): a ray depends only on the seed, its stream, its pixel
// (or path) and its sample (or bounce).
#include <cstdint>
#include <glm/vec2.hpp>
#include <vector>

#include "geometry/ray.h"
#include "scene/camera.h"

namespace edacrt {

// Independent random streams.
inline constexpr std::uint32_t kJitterStream = 0x1f0e3d5bu;  // subpixel positions
inline constexpr std::uint32_t kBounceStream = 0x7a3c9e21u;  // diffuse bounces

/// The key of one random 2D sample.
std::uint32_t sample_key(std::uint32_t seed, std::uint32_t stream, std::uint32_t pixel,
                         std::uint32_t sample);

/// Two floats in [0, 1) from a key.
glm::vec2 random_2d(std::uint32_t key);

/// spp jittered rays per pixel of a width x height image, a pixel's samples together, rows
/// from the top.
std::vector<Ray> jittered_camera_rays(const PinholeProjection& projection, int width, int height,
                                      int spp, std::uint32_t seed);

}  // namespace edacrt
