#pragma once
// Closest hits in double precision, by brute force: the yardstick of the hit-accuracy report.
// Möller-Trumbore on the exact float inputs, evaluated in double.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "geometry/ray.h"
#include "geometry/triangle.h"

namespace edacrt {

struct ReferenceHit {
    double t = 0.0;
    std::int32_t prim = -1;  // -1: miss
};

/// The double-precision distance at which `ray` hits `tri`, if it does within [tmin, tmax].
std::optional<double> intersect_double(const Ray& ray, const Triangle& tri);

/// The closest hit of every ray among `triangles` (in parallel).
std::vector<ReferenceHit> reference_hits(std::span<const Triangle> triangles,
                                         std::span<const Ray> rays);

}  // namespace edacrt
