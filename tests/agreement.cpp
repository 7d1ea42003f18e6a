#include "agreement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "scene/camera.h"
#include "trace/naive_tracer.h"

namespace edacrt::test {

RaySets make_ray_sets(const Scene& scene, std::uint32_t seed, float surface_tmin, float share) {
    const auto count = [&](int n) { return int(float(n) * share); };
    const int width = int(64.0f * std::sqrt(share)), height = int(48.0f * std::sqrt(share));
    RaySets out;
    const Aabb box = scene.bounds();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto inside = [&] {
        return box.lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * box.extent();
    };
    const auto direction = [&] {
        glm::vec3 d;
        do d = glm::vec3(unit(rng), unit(rng), unit(rng)) * 2.0f - 1.0f;
        while (glm::dot(d, d) > 1.0f || glm::dot(d, d) < 1e-4f);
        return glm::normalize(d);
    };

    std::vector<Ray> camera;
    const Camera cam = scene.camera.value_or(frame_box(box));
    const PinholeProjection projection(cam, width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            camera.push_back(projection.ray(x + unit(rng), y + unit(rng)));
    out.sets.emplace_back("camera", std::move(camera));

    std::vector<Ray> random;
    for (int i = 0; i < count(2500); ++i) random.push_back({inside(), direction()});
    out.sets.emplace_back("random inside", std::move(random));

    std::vector<Ray> on_surface;
    for (int i = 0; i < count(2000); ++i) {
        const Triangle tri = scene.corners(rng() % scene.triangle_count());
        const float a = unit(rng), b = unit(rng) * (1.0f - a);
        const glm::vec3 p = (1 - a - b) * tri.p0 + a * tri.p1 + b * tri.p2;
        on_surface.push_back({p, direction(), surface_tmin});
    }
    out.sets.emplace_back("from surfaces", std::move(on_surface));

    std::vector<Ray> axis_parallel;
    for (int i = 0; i < count(2000); ++i) {
        glm::vec3 d(0.0f);
        d[i % 3] = (i / 3) % 2 ? 1.0f : -1.0f;
        if (i % 4 == 0) d[(i + 1) % 3] = -0.0f;
        axis_parallel.push_back({inside(), d});
    }
    out.sets.emplace_back("axis-parallel", std::move(axis_parallel));

    std::vector<Ray> segments;
    const float scale = glm::length(box.extent());
    for (int i = 0; i < count(2000); ++i)
        segments.push_back({inside(), direction(), 0.05f * scale * unit(rng),
                            0.2f * scale * unit(rng) + 0.05f * scale});
    out.sets.emplace_back("finite tmax", std::move(segments));
    return out;
}

Reference make_reference(const Scene& scene, float surface_tmin, float share) {
    Reference ref{make_ray_sets(scene, 42, surface_tmin, share), {}, {}};
    NaiveTracer naive;
    naive.set_scene(scene);
    for (const auto& [name, rays] : ref.sets.sets) {
        ref.closest.emplace_back(rays.size());
        ref.any.emplace_back(rays.size());
        naive.trace(rays, ref.closest.back(), Query::closest);
        naive.trace(rays, ref.any.back(), Query::any);
    }
    return ref;
}

float reintersect(const Scene& scene, const Ray& ray, std::int32_t prim) {
    TriangleHit hit;
    return intersect_triangle(make_watertight_ray(ray), scene.corners(std::size_t(prim)), ray.tmin,
                              ray.tmax, hit)
               ? hit.t
               : NAN;
}

void expect_agreement(const Scene& scene, const Reference& ref, Tracer& tracer,
                      const std::string& label, bool exact) {
    const float scale = exact ? 0.0f : glm::length(scene.bounds().extent());
    const auto tolerance = [&](float t) { return 1e-6f * (std::abs(t) + scale); };
    const auto expect_reintersects = [&](const Ray& ray, const Hit& hit) {
        const float t = reintersect(scene, ray, hit.prim);
        return exact ? t == hit.t : std::abs(t - hit.t) <= tolerance(hit.t);
    };
    // Our kernel rejects hits whose t is within its rounding bound of 0 (triangle.h); for a ray
    // nearly parallel to the triangle that bound is large, and another kernel may decide such
    // an ill-conditioned hit the other way. Tolerated for other kernels only, and rarely.
    const auto grazing = [&](const Ray& ray, const Hit& a, const Hit& b) {
        for (const Hit* h : {&a, &b})
            if (h->hit()) {
                const glm::vec3 n = unit_normal(scene.corners(std::size_t(h->prim)));
                if (std::abs(glm::dot(n, glm::normalize(ray.dir))) < 1e-3f) return true;
            }
        return false;
    };
    std::size_t ill_conditioned = 0;
    for (std::size_t set = 0; set < ref.sets.sets.size(); ++set) {
        const auto& [name, rays] = ref.sets.sets[set];
        const std::vector<Hit>& expected = ref.closest[set];
        std::vector<Hit> got(rays.size());
        tracer.trace(rays, got, Query::closest);
        std::size_t hits = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if (!exact &&
                (got[i].hit() != expected[i].hit() ||
                 std::abs(got[i].t - expected[i].t) > tolerance(expected[i].t)) &&
                grazing(rays[i], got[i], expected[i])) {
                ++ill_conditioned;
                continue;
            }
            ASSERT_EQ(got[i].hit(), expected[i].hit()) << label << ", " << name << ", ray " << i;
            if (!expected[i].hit()) continue;
            ++hits;
            ASSERT_NEAR(got[i].t, expected[i].t, tolerance(expected[i].t))
                << label << ", " << name << ", ray " << i;
            if (got[i].prim != expected[i].prim) {
                // A tie (coplanar or duplicated triangles, a shared edge): the other triangle
                // must really be hit at the distance reported.
                ASSERT_TRUE(expect_reintersects(rays[i], got[i]))
                    << label << ", " << name << ", ray " << i << ", t " << got[i].t;
            }
        }
        if (name == "camera") {
            EXPECT_GT(hits, 0u) << label;
        }

        tracer.trace(rays, got, Query::any);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if (!exact && got[i].hit() != ref.any[set][i].hit() &&
                grazing(rays[i], got[i], ref.closest[set][i])) {
                ++ill_conditioned;
                continue;
            }
            ASSERT_EQ(got[i].hit(), ref.any[set][i].hit())
                << label << ", any hit, " << name << ", ray " << i;
            if (got[i].hit()) {  // the reported occluder really blocks the ray there
                ASSERT_TRUE(expect_reintersects(rays[i], got[i]))
                    << label << ", any hit, " << name << ", ray " << i << ", t " << got[i].t;
            }
        }
    }
    EXPECT_LE(ill_conditioned, 3u) << label << ": grazing disagreements";
}

}  // namespace edacrt::test
