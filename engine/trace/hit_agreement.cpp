#include "trace/hit_agreement.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace edacrt {
namespace {

bool same_t(float a, float b) { return std::abs(a - b) <= 1e-6f * std::abs(b); }

/// Whether the ray hits triangle `prim` (at t, when `t` is given).
bool really_hits(std::span<const Triangle> triangles, const Ray& ray, std::int32_t prim,
                 const float* t) {
    TriangleHit hit;
    return intersect_triangle(make_watertight_ray(ray), triangles[std::size_t(prim)], ray.tmin,
                              ray.tmax, hit) &&
           (!t || same_t(hit.t, *t));
}

bool ill_conditioned(std::span<const Triangle> triangles, const Ray& ray, const Hit& hit) {
    if (!hit.hit()) return false;
    const float edge = std::min({hit.u, hit.v, 1.0f - hit.u - hit.v});
    const glm::vec3 n = unit_normal(triangles[std::size_t(hit.prim)]);
    return edge < 1e-4f || std::abs(glm::dot(n, glm::normalize(ray.dir))) < 1e-3f;
}

}  // namespace

Agreement compare_hits(std::span<const Triangle> triangles, std::span<const Ray> rays,
                       std::span<const Hit> expected, std::span<const Hit> got, Query query,
                       bool exact) {
    Agreement a;
    a.rays = rays.size();
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Hit &e = expected[i], &g = got[i];
        bool agree = e.hit() == g.hit();
        if (agree && g.hit()) {
            if (query == Query::any) {
                agree = really_hits(triangles, rays[i], g.prim, nullptr);
            } else if (g.prim == e.prim) {
                agree = same_t(g.t, e.t);
            } else {
                agree = same_t(g.t, e.t) && really_hits(triangles, rays[i], g.prim, &g.t);
                a.ties += agree;
            }
        }
        if (agree) continue;
        if (!exact &&
            (ill_conditioned(triangles, rays[i], e) || ill_conditioned(triangles, rays[i], g))) {
            ++a.tolerated;
            continue;
        }
        if (a.disagreements++ == 0) a.first_disagreement = std::int64_t(i);
    }
    return a;
}

}  // namespace edacrt
