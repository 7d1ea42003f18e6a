#include "trace/reference_hits.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <glm/geometric.hpp>

namespace edacrt {

std::optional<double> intersect_double(const Ray& ray, const Triangle& tri) {
    const glm::dvec3 p0(tri.p0), e1 = glm::dvec3(tri.p1) - p0, e2 = glm::dvec3(tri.p2) - p0;
    const glm::dvec3 dir(ray.dir);
    const glm::dvec3 p = glm::cross(dir, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return std::nullopt;
    const glm::dvec3 s = glm::dvec3(ray.org) - p0;
    const double u = glm::dot(s, p) / det;
    if (u < 0.0 || u > 1.0) return std::nullopt;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(dir, q) / det;
    if (v < 0.0 || u + v > 1.0) return std::nullopt;
    const double t = glm::dot(e2, q) / det;
    // Within double rounding of 0 (2^-40 of the coordinates, far below float resolution) is
    // not a hit: a ray spawned just off its own triangle must not "hit" it at t = 1e-13.
    const double scale =
        std::max({glm::length(glm::dvec3(ray.org)), glm::length(p0),
                  glm::length(glm::dvec3(tri.p1)), glm::length(glm::dvec3(tri.p2))});
    const double zero = 0x1p-40 * scale / glm::length(dir);
    if (!(t >= double(ray.tmin) && t <= double(ray.tmax)) || t <= zero) return std::nullopt;
    return t;
}

std::vector<ReferenceHit> reference_hits(std::span<const Triangle> triangles,
                                         std::span<const Ray> rays) {
    std::vector<ReferenceHit> hits(rays.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 16), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
            for (std::size_t prim = 0; prim < triangles.size(); ++prim)
                if (const auto t = intersect_double(rays[i], triangles[prim]))
                    if (hits[i].prim < 0 || *t < hits[i].t) hits[i] = {*t, std::int32_t(prim)};
    });
    return hits;
}

}  // namespace edacrt
