#include "trace/naive_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <functional>

#include "trace/ray_observer.h"

namespace edacrt {
namespace {

/// Tests the ray against the triangles in order; returns how many tests it made.
template <Query Q>
std::size_t intersect_all(const Ray& ray, std::span<const Triangle> triangles, Hit& hit) {
    const WatertightRay wray = make_watertight_ray(ray);
    hit = Hit{};
    float t_far = ray.tmax;
    TriangleHit candidate;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        if (!intersect_triangle(wray, triangles[i], ray.tmin, t_far, candidate)) continue;
        hit = {candidate.t, static_cast<std::int32_t>(i), candidate.u, candidate.v};
        if constexpr (Q == Query::any) return i + 1;
        t_far = candidate.t;
    }
    return triangles.size();
}

/// Returns the number of ray-triangle tests; each ray's goes to `observer` (ray_observer.h).
template <Query Q, class Observer>
std::uint64_t trace_all(std::span<const Triangle> triangles, std::span<const Ray> rays,
                        std::span<Hit> hits, const Observer& observer) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, rays.size(), 64), std::uint64_t{0},
        [&](const auto& range, std::uint64_t tests) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const std::size_t ray_tests = intersect_all<Q>(rays[i], triangles, hits[i]);
                observer.traced(i, 0, std::uint32_t(ray_tests));
                tests += ray_tests;
            }
            return tests;
        },
        std::plus<>());
}

}  // namespace

void NaiveTracer::set_scene(const Scene& scene) { gather_triangles(scene, triangles_); }

UpdateWork NaiveTracer::update(const Scene& scene, SceneUpdate) {
    set_scene(scene);
    return UpdateWork::none;
}

TraceStats NaiveTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                    TraceDetail* detail) {
    return with_ray_observer(detail, [&](const auto& observer) {
        TraceStats stats;
        stats.rays = rays.size();
        stats.ray_triangle_tests = query == Query::closest
                                       ? trace_all<Query::closest>(triangles_, rays, hits, observer)
                                       : trace_all<Query::any>(triangles_, rays, hits, observer);
        return stats;
    });
}

}  // namespace edacrt
