#include "heatmap.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>

namespace edacrt::app {

std::vector<float> heat_values(std::span<const RayStats> pixels, View view) {
    std::vector<float> values(pixels.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        const RayStats& r = pixels[i];
        switch (view) {
            case View::render:
                break;
            case View::box_tests:
                values[i] = float(r.ray_box_tests);
                break;
            case View::triangle_tests:
                values[i] = float(r.ray_triangle_tests);
                break;
            case View::depth:
                values[i] = float(r.deepest_level);
                break;
            case View::order_misses:
                values[i] = float(r.order_misses);
                break;
        }
    }
    return values;
}

glm::vec3 turbo(float t) {
    t = std::clamp(t, 0.0f, 1.0f);
    const float t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
    const glm::vec3 c = glm::vec3(0.13572138f, 0.09140261f, 0.10667330f) +
                        glm::vec3(4.61539260f, 2.19418839f, 12.64194608f) * t +
                        glm::vec3(-42.66032258f, 4.84296658f, -60.58204836f) * t2 +
                        glm::vec3(132.13108234f, -14.18503333f, 110.36276771f) * t3 +
                        glm::vec3(-152.94239396f, 4.27729857f, -89.90310912f) * t4 +
                        glm::vec3(59.28637943f, 2.82956604f, 27.34824973f) * t5;
    return glm::clamp(c, 0.0f, 1.0f);
}

glm::vec3 diverging(float t) {
    const glm::vec3 end = t < 0.0f ? glm::vec3(0.23f, 0.45f, 0.95f) : glm::vec3(0.95f, 0.3f, 0.2f);
    const float f = std::min(1.0f, std::abs(t));
    return glm::vec3(1.0f) + f * (end - glm::vec3(1.0f));
}

}  // namespace edacrt::app
