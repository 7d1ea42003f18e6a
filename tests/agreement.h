#pragma once
// Tracers against the naive reference on the same rays, shared by the static and the dynamic
// (animated) agreement tests: identical hit/miss, t within 1e-6 relative, the same triangle
// unless two are hit at the same t.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"
#include "trace/tracer.h"

namespace edacrt::test {

struct RaySets {
    std::vector<std::pair<std::string, std::vector<Ray>>> sets;
};

/// Camera rays, random rays from inside, rays starting on surfaces (with tmin = surface_tmin),
/// axis-parallel rays, short segments: 64x48 camera rays and 2000-2500 rays of each other kind,
/// times `share`.
RaySets make_ray_sets(const Scene& scene, std::uint32_t seed, float surface_tmin = 0.0f,
                      float share = 1.0f);

/// The naive tracer's answers for every ray set of a scene, computed once.
struct Reference {
    RaySets sets;
    std::vector<std::vector<Hit>> closest, any;
};

Reference make_reference(const Scene& scene, float surface_tmin = 0.0f, float share = 1.0f);

/// The t at which `ray` hits triangle `prim`, or NaN.
float reintersect(const Scene& scene, const Ray& ray, std::int32_t prim);

/// `exact`: the tracer uses our intersection kernel, so distances agree within 1e-6 of t and
/// a reported triangle re-intersects at exactly the reported t. Otherwise (Embree's own
/// arithmetic, whose rounding scales with the coordinates rather than with t) both hold within
/// 1e-6 of (t + the scene's diagonal).
/// The tracer must already hold `scene` (set_scene or update_scene).
void expect_agreement(const Scene& scene, const Reference& ref, Tracer& tracer,
                      const std::string& label, bool exact);

}  // namespace edacrt::test
