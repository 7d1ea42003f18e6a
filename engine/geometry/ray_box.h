#pragma once
// Robust ray/box slab test (Ize, "Robust BVH Ray Traversal", JCGT 2013; pbrt-v4
// Bounds3::IntersectP).
#include <cmath>
#include <glm/vec3.hpp>
#include <limits>

#include "geometry/aabb.h"
#include "geometry/ray.h"

namespace edacrt {

/// gamma(n) = n * u / (1 - n * u), the bound on relative rounding error of n operations.
constexpr float gamma_bound(int n) {
    constexpr float u = std::numeric_limits<float>::epsilon() * 0.5f;
    return (n * u) / (1.0f - n * u);
}

/// A ray prepared for slab tests: 1/dir is +inf or -inf for a +0 or -0 direction component.
struct SlabRay {
    glm::vec3 org;
    glm::vec3 inv_dir;
    float tmin;
    float tmax;
};

inline SlabRay make_slab_ray(const Ray& ray) {
    return {ray.org, 1.0f / ray.dir, ray.tmin, ray.tmax};
}

/// Conservative slab test over [ray.tmin, t_far]: never misses a box the exact ray touches.
/// On a hit, t_entry is the (clamped) entry distance. The near plane of each axis is chosen by
/// the sign of 1/dir (Williams et al. 2005), so -0 and +0 directions pick the right side, and
/// each far distance is scaled by 1 + 2 * gamma(3) to cover rounding (Ize 2013). When the
/// origin lies on a slab plane of an axis the ray is parallel to, (plane - org) * inf is
/// 0 * inf = NaN; the comparisons are ordered so that a NaN never replaces a bound, i.e. that
/// plane imposes no constraint (the ray grazes the face, which counts as a hit).
/// Always inlined and without an early exit per axis: the three axes run branch-free (t0 only
/// grows and t1 only shrinks, so testing once at the end gives the same answer).
[[gnu::always_inline]] inline bool intersect_box(const SlabRay& ray, const Aabb& box, float t_far,
                                                 float& t_entry) {
    float t0 = ray.tmin;
    float t1 = t_far;
    for (int axis = 0; axis < 3; ++axis) {
        const bool negative = std::signbit(ray.inv_dir[axis]);
        const float near_plane = negative ? box.hi[axis] : box.lo[axis];
        const float far_plane = negative ? box.lo[axis] : box.hi[axis];
        const float t_near_axis = (near_plane - ray.org[axis]) * ray.inv_dir[axis];
        const float t_far_axis =
            (far_plane - ray.org[axis]) * ray.inv_dir[axis] * (1.0f + 2.0f * gamma_bound(3));
        t0 = t_near_axis > t0 ? t_near_axis : t0;
        t1 = t_far_axis < t1 ? t_far_axis : t1;
    }
    t_entry = t0;
    return t0 <= t1;
}

}  // namespace edacrt
