#pragma once
// Whether two methods found the same hits for the same rays (the check of `edacrt bench`).
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/ray.h"
#include "geometry/triangle.h"
#include "trace/tracer.h"

namespace edacrt {

struct Agreement {
    std::uint64_t rays = 0;
    std::uint64_t ties = 0;       // another triangle, hit at the same t (1e-6 relative)
    std::uint64_t tolerated = 0;  // ill-conditioned rays where Embree may differ (see below)
    std::uint64_t disagreements = 0;
    std::int64_t first_disagreement = -1;  // ray index
};

/// Compares `got` with `expected` ray by ray, as tests/tracer_agreement_test.cpp does: the same
/// hit or miss; for closest hits the same t (1e-6 relative) on the same triangle or on a
/// triangle the ray really hits at that t; for any hit, an occluder the ray really hits. When
/// `exact` is false (Embree, whose robust mode is not watertight: README, Robustness), a
/// difference is tolerated where either hit is within 1e-4 (barycentric) of an edge of its
/// triangle or the ray grazes it (|cos| < 1e-3).
Agreement compare_hits(std::span<const Triangle> triangles, std::span<const Ray> rays,
                       std::span<const Hit> expected, std::span<const Hit> got, Query query,
                       bool exact);

}  // namespace edacrt
