#include "render/benchmark_rays.h"

#include "util/hash_random.h"

namespace edacrt {

std::uint32_t sample_key(std::uint32_t seed, std::uint32_t stream, std::uint32_t pixel,
                         std::uint32_t sample) {
    return hash_combine(hash_combine(hash_combine(seed, stream), pixel), sample);
}

glm::vec2 random_2d(std::uint32_t key) {
    return {hash_to_unit_float(key), hash_to_unit_float(pcg_hash(key))};
}

std::vector<Ray> jittered_camera_rays(const PinholeProjection& projection, int width, int height,
                                      int spp, std::uint32_t seed) {
    std::vector<Ray> rays;
    rays.reserve(std::size_t(width) * std::size_t(height) * std::size_t(spp));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const auto pixel = std::uint32_t(y * width + x);
            for (int s = 0; s < spp; ++s) {
                const glm::vec2 u =
                    random_2d(sample_key(seed, kJitterStream, pixel, std::uint32_t(s)));
                rays.push_back(projection.ray(float(x) + u.x, float(y) + u.y));
            }
        }
    return rays;
}

}  // namespace edacrt
