#pragma once
#include <cstdint>
#include <glm/vec3.hpp>
#include <limits>

namespace edacrt {

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// The segment org + t * dir, t in [tmin, tmax]. Same layout as one record of a ray file.
struct Ray {
    glm::vec3 org{0.0f};
    glm::vec3 dir{0.0f, 0.0f, 1.0f};
    float tmin = 0.0f;
    float tmax = kInfinity;
};
static_assert(sizeof(Ray) == 32, "a ray file record is 8 float32");

/// The closest (or, for occlusion queries, any) hit of a ray. prim == -1 is a miss.
/// Barycentrics follow Embree: the hit point is (1 - u - v) * p0 + u * p1 + v * p2.
/// Same layout as one record of a hit file.
struct Hit {
    float t = kInfinity;
    std::int32_t prim = -1;
    float u = 0.0f;
    float v = 0.0f;

    bool hit() const { return prim >= 0; }
};
static_assert(sizeof(Hit) == 16, "a hit file record is 16 bytes");

}  // namespace edacrt
