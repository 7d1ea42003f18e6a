#pragma once
// Spawning rays from surfaces without a scene-scale epsilon (pbrt-v3 section 3.9,
// pbrt-v4's OffsetRayOrigin): the hit point is computed with a bound on its rounding error, and
// the origin of a secondary ray moves along the geometric normal just past that bound; the
// triangle test in turn accepts only hits whose t is conservatively positive (triangle.h).
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>

#include "geometry/triangle.h"

namespace edacrt {

/// A point on a triangle and a per-axis bound on the error of its computation.
struct SurfacePoint {
    glm::vec3 p;
    glm::vec3 error;
};

/// The point (1-u-v) p0 + u p1 + v p2. The bound covers the interpolation and the error of
/// the barycentrics themselves (pbrt-v3's gamma(7) bound for watertight triangle hits).
inline SurfacePoint surface_point(const Triangle& tri, float u, float v) {
    const float w = 1.0f - u - v;
    const glm::vec3 a = w * tri.p0, b = u * tri.p1, c = v * tri.p2;
    return {a + b + c, rounding_gamma<float>(7) * (glm::abs(a) + glm::abs(b) + glm::abs(c))};
}

/// The origin for a ray leaving `point` towards `direction`: moved along the unit geometric
/// normal `n` to the side `direction` points into, past the error box, then rounded away by
/// at least one ulp on every axis the normal has a component in (so an exact point, whose
/// error bound is 0, still leaves its plane).
inline glm::vec3 offset_ray_origin(const SurfacePoint& point, glm::vec3 n, glm::vec3 direction) {
    if (glm::dot(direction, n) < 0.0f) n = -n;
    const glm::vec3 origin = point.p + glm::dot(glm::abs(n), point.error) * n;
    glm::vec3 out = origin;
    for (int axis = 0; axis < 3; ++axis) {
        if (n[axis] > 0.0f)
            out[axis] = std::nextafter(origin[axis], std::numeric_limits<float>::infinity());
        else if (n[axis] < 0.0f)
            out[axis] = std::nextafter(origin[axis], -std::numeric_limits<float>::infinity());
    }
    return out;
}

/// tmin of spawned rays: the smallest positive normal float, so a hit computed at t = 0 (the
/// ray's own surface, rounded) is rejected, at no scale-dependent cost. Not a denormal:
/// Embree's threads run with denormals-are-zero, which would read it as 0.
inline constexpr float kSpawnTmin = std::numeric_limits<float>::min();

}  // namespace edacrt
