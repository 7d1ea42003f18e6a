#pragma once
#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "geometry/ray.h"

namespace edacrt {

/// Axis-aligned box. Default-constructed it is empty (lo = +inf, hi = -inf), so extending it
/// with the first point yields that point.
struct Aabb {
    glm::vec3 lo{kInfinity};
    glm::vec3 hi{-kInfinity};

    void extend(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void extend(const Aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    bool contains(const glm::vec3& p) const {
        return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z &&
               p.z <= hi.z;
    }
    glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : hi - lo; }
    glm::vec3 center() const { return 0.5f * (lo + hi); }
    float surface_area() const {
        const glm::vec3 e = extent();
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
    int longest_axis() const {
        const glm::vec3 e = extent();
        return e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
    }
};

}  // namespace edacrt
