// Per-level and per-ray statistics are consistent with the totals and with each other, and
// collecting them does not change a single hit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "scene/builtin_scenes.h"
#include "trace/edacrt_tracer.h"

namespace edacrt {
namespace {

std::vector<Ray> camera_and_random_rays(const Scene& scene) {
    std::vector<Ray> rays =
        PinholeProjection(scene.camera.value_or(frame_box(scene.bounds())), 80, 60)
            .pixel_centre_rays();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
    for (int i = 0; i < 3000; ++i)
        rays.push_back({{coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), 0.5f}});
    return rays;
}

void expect_consistent(Tracer& tracer, const Scene& scene, Query query, const std::string& label) {
    SCOPED_TRACE(label);
    tracer.set_scene(scene);
    const std::vector<Ray> rays = camera_and_random_rays(scene);
    std::vector<Hit> fast(rays.size()), detailed(rays.size());
    const TraceStats fast_totals = tracer.trace(rays, fast, query);
    TraceDetail detail;
    const TraceStats totals = tracer.trace(rays, detailed, query, &detail);

    // Statistics change nothing.
    ASSERT_EQ(std::memcmp(fast.data(), detailed.data(), fast.size() * sizeof(Hit)), 0);
    EXPECT_EQ(fast_totals.ray_box_tests, totals.ray_box_tests);
    EXPECT_EQ(fast_totals.ray_triangle_tests, totals.ray_triangle_tests);

    // Per-ray counts add up to the totals.
    ASSERT_EQ(detail.rays.size(), rays.size());
    std::uint64_t ray_box = 0, ray_tri = 0, ray_order_misses = 0;
    for (const RayStats& r : detail.rays) {
        ray_box += r.ray_box_tests;
        ray_tri += r.ray_triangle_tests;
        ray_order_misses += r.order_misses;
    }
    EXPECT_EQ(ray_box, totals.ray_box_tests);
    EXPECT_EQ(ray_tri, totals.ray_triangle_tests);
    if (tracer.method() == Method::bvh || tracer.method() == Method::naive) {
        EXPECT_TRUE(detail.levels.empty());
        return;
    }

    // Per-level counts add up to the totals and to each other.
    ASSERT_GT(detail.levels.size(), 3u);
    std::uint64_t level_box = 0, level_tri = 0, level_order_misses = 0;
    for (std::size_t d = 0; d < detail.levels.size(); ++d) {
        const LevelStats& level = detail.levels[d];
        level_box += level.ray_box_tests;
        level_tri += level.ray_triangle_tests;
        level_order_misses += level.order_misses;
        const std::uint64_t inner = level.nodes - level.leaves;
        EXPECT_EQ(level.filters_done + level.filters_skipped, 2 * inner) << "level " << d;
        if (d + 1 < detail.levels.size()) {
            EXPECT_EQ(level.rays_passed, detail.levels[d + 1].rays_in) << "level " << d;
            EXPECT_LE(detail.levels[d + 1].nodes, 2 * inner) << "level " << d;
        } else {
            EXPECT_EQ(level.rays_passed, 0u);
        }
        EXPECT_LE(level.triangles, level.nodes * scene.triangle_count());
    }
    EXPECT_EQ(level_box, totals.ray_box_tests);
    EXPECT_EQ(level_tri, totals.ray_triangle_tests);
    EXPECT_EQ(level_order_misses, ray_order_misses);
    EXPECT_LE(detail.levels[0].rays_in, rays.size());
    EXPECT_EQ(detail.levels[0].triangles, detail.levels[0].nodes * scene.triangle_count());
    EXPECT_GT(detail.levels[0].order_hits + detail.levels[0].order_misses, 0u);
}

TEST(TraceStats, EdacrtLevelsAndRaysAreConsistent) {
    const Scene scene = make_builtin_scene("builtin:sphere:subdiv=4");
    for (const Query query : {Query::closest, Query::any}) {
        EdacrtTracer edacrt;
        expect_consistent(edacrt, scene, query, "edacrt");
        EdacrtTracer dacrt(dacrt_params(), Method::dacrt);
        expect_consistent(dacrt, scene, query, "dacrt");
    }
}

TEST(TraceStats, FilterCountsFollowTheFilterSkipSetting) {
    const Scene scene = make_builtin_scene("builtin:soup:count=4000,seed=8");
    const std::vector<Ray> rays = camera_and_random_rays(scene);
    std::vector<Hit> hits(rays.size());
    for (const bool skip : {false, true}) {
        EdacrtParams params;
        params.filter_skip = skip;
        params.cost_filter = skip ? 1e9f : params.cost_filter;  // skipping everywhere
        EdacrtTracer tracer(params);
        tracer.set_scene(scene);
        TraceDetail detail;
        tracer.trace(rays, hits, Query::closest, &detail);
        std::uint64_t done = 0, skipped = 0, sampled = 0, candidates = 0;
        for (const LevelStats& level : detail.levels) {
            done += level.filters_done;
            skipped += level.filters_skipped;
            sampled += level.sampled_rays;
            candidates += level.candidate_splits;
        }
        EXPECT_GT(skip ? skipped : done, 0u);
        EXPECT_EQ(skip ? done : skipped, 0u);
        EXPECT_GT(sampled, 0u);
        EXPECT_GT(candidates, 0u);
    }
}

TEST(TraceStats, NaiveAndBvhFillPerRayCounts) {
    const Scene scene = make_builtin_scene("builtin:sphere:subdiv=3");
    for (const Method method : {Method::naive, Method::bvh}) {
        const auto tracer = make_tracer(method);
        expect_consistent(*tracer, scene, Query::closest, std::string(method_name(method)));
    }
}

}  // namespace
}  // namespace edacrt
