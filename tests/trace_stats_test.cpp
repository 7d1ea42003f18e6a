// Per-level and per-ray statistics are consistent with the totals and with each other, and
// collecting them does not change a single hit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
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
        EXPECT_EQ(level.ray_box_tests, level.sample_box_tests + level.filter_box_tests);
        EXPECT_LE(level.culled_by_distance, level.filter_box_tests);
        EXPECT_EQ(level.alpha_children, 2 * (level.nodes - level.leaves));
        std::uint64_t binned = 0, sources = 0;
        for (const std::uint64_t n : level.alpha_error_bins) binned += n;
        for (const std::uint64_t n : level.alpha_sources) sources += n;
        EXPECT_EQ(binned, level.alpha_children);
        EXPECT_EQ(2 * sources, level.alpha_children);
        EXPECT_LE(level.alpha_error_quantile(0.5), level.alpha_error_quantile(0.9));
        EXPECT_LE(level.alpha_error_quantile(0.9), level.alpha_error_max);
        EXPECT_LE(level.alpha_error_sum, level.alpha_error_max * double(level.alpha_children));
        const std::uint64_t inner = level.nodes - level.leaves;
        // Two child ray sets per inner node, three where the second child was split.
        EXPECT_LE(level.second_splits, inner);
        const std::uint64_t child_sets = 2 * inner + level.second_splits;
        EXPECT_EQ(level.filters_done + level.filters_skipped, child_sets) << "level " << d;
        if (d + 1 < detail.levels.size()) {
            EXPECT_EQ(level.rays_passed, detail.levels[d + 1].rays_in) << "level " << d;
            EXPECT_LE(detail.levels[d + 1].nodes, child_sets) << "level " << d;
        } else {
            EXPECT_EQ(level.rays_passed, 0u);
        }
        EXPECT_LE(level.triangles, level.nodes * detail.levels[0].triangles);
    }
    // The root filter tests every ray once, outside the levels; one root node.
    EXPECT_EQ(detail.root.rays, rays.size());
    EXPECT_EQ(detail.root.box_tests, rays.size());
    EXPECT_EQ(level_box + detail.root.box_tests, totals.ray_box_tests);
    EXPECT_EQ(level_tri, totals.ray_triangle_tests);
    EXPECT_EQ(level_order_misses, ray_order_misses);
    EXPECT_EQ(detail.levels[0].nodes, 1u);
    EXPECT_EQ(detail.levels[0].rays_in, detail.root.entered);
    // The root holds every triangle, or with pre-splitting (EDACRT's default, 0.3 extra pieces
    // per triangle) every piece.
    EXPECT_GE(detail.levels[0].triangles, scene.triangle_count());
    EXPECT_LE(detail.levels[0].triangles, scene.triangle_count() * 14 / 10);
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
        // With a huge C_bv the per-triangle rule skips everywhere (the paper's rule would still
        // filter inner children with alpha <= 1/2).
        params.filter_skip = skip ? FilterSkip::triangles : FilterSkip::off;
        params.cost_filter = skip ? 1e9f : params.cost_filter;  // skipping everywhere
        EdacrtTracer tracer(params);
        tracer.set_scene(scene);
        TraceDetail detail;
        tracer.trace(rays, hits, Query::closest, &detail);
        std::uint64_t done = 0, skipped = 0, sampled = 0, candidates = 0;
        for (std::size_t depth = 0; depth < detail.levels.size(); ++depth) {
            const LevelStats& level = detail.levels[depth];
            // Except that in the root and its children a first child is filtered for the
            // second child's task (on more than one thread): at most one filter per node.
            if (skip && depth < 2)
                EXPECT_LE(level.filters_done, level.nodes);
            else
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
        expect_consistent(*tracer, scene, Query::closest, std::string(enum_name(kMethods, method)));
    }
}

TEST(TraceStats, RecordedNodeRaysAndHitLeavesTellTheStepThroughStory) {
    const Scene scene = make_builtin_scene("builtin:sphere:subdiv=4");
    const std::vector<Ray> rays = camera_and_random_rays(scene);
    for (const std::size_t budget : {std::size_t(1) << 24, std::size_t(5000)}) {
        SCOPED_TRACE(budget);
        EdacrtTracer tracer;
        tracer.set_scene(scene);
        std::vector<Hit> hits(rays.size());
        TraceDetail detail;
        detail.max_nodes = 1'000'000;
        detail.max_node_ray_ids = budget;
        tracer.trace(rays, hits, Query::closest, &detail);
        ASSERT_FALSE(detail.nodes.empty());
        EXPECT_LE(detail.node_ray_ids.size(), budget);
        // Each node's ids: its own count, distinct, and a subset of its parent's.
        std::size_t with_ids = 0;
        for (const NodeRecord& n : detail.nodes) {
            if (n.ray_ids < 0) continue;
            ++with_ids;
            const auto begin = detail.node_ray_ids.begin() + n.ray_ids;
            std::vector<std::uint32_t> ids(begin, begin + n.rays);
            std::sort(ids.begin(), ids.end());
            EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end());
            if (n.parent < 0) continue;
            const NodeRecord& p = detail.nodes[std::size_t(n.parent)];
            if (p.ray_ids < 0) continue;
            std::vector<std::uint32_t> parent(detail.node_ray_ids.begin() + p.ray_ids,
                                              detail.node_ray_ids.begin() + p.ray_ids + p.rays);
            std::sort(parent.begin(), parent.end());
            EXPECT_TRUE(std::includes(parent.begin(), parent.end(), ids.begin(), ids.end()));
        }
        EXPECT_GT(with_ids, 0u);
        if (budget > 1'000'000) {
            EXPECT_EQ(with_ids, detail.nodes.size());
        }
        // hit_node: exactly the rays that hit, each at a recorded leaf that holds the ray.
        ASSERT_EQ(detail.hit_node.size(), rays.size());
        for (std::size_t r = 0; r < rays.size(); ++r) {
            EXPECT_EQ(detail.hit_node[r] >= 0, hits[r].hit()) << r;
            if (detail.hit_node[r] < 0) continue;
            const NodeRecord& leaf = detail.nodes[std::size_t(detail.hit_node[r])];
            EXPECT_TRUE(leaf.leaf);
            if (leaf.ray_ids < 0) continue;
            const auto begin = detail.node_ray_ids.begin() + leaf.ray_ids;
            EXPECT_NE(std::find(begin, begin + leaf.rays, std::uint32_t(r)), begin + leaf.rays);
        }
    }
}

TEST(TraceStats, RecordedNodesAndAFollowedRayDescribeTheRecursion) {
    const Scene scene = make_builtin_scene("builtin:sphere:subdiv=4");
    const std::vector<Ray> rays = camera_and_random_rays(scene);
    EdacrtTracer tracer;
    tracer.set_scene(scene);
    std::vector<Hit> fast(rays.size()), hits(rays.size());
    tracer.trace(rays, fast, Query::closest);
    const std::size_t followed = 80 * 30 + 40;  // a camera ray through the sphere's middle
    TraceDetail detail;
    detail.max_nodes = 1'000'000;
    detail.follow_ray = std::int64_t(followed);
    tracer.trace(rays, hits, Query::closest, &detail);
    ASSERT_EQ(std::memcmp(fast.data(), hits.data(), fast.size() * sizeof(Hit)), 0);
    ASSERT_TRUE(hits[followed].hit());

    // Nodes: the per-level sums match the level table; links are consistent; a split node
    // keeps all K - 1 candidates and chose the cheapest.
    ASSERT_FALSE(detail.nodes.empty());
    std::vector<std::uint64_t> rays_in(detail.levels.size()), nodes(detail.levels.size());
    std::vector<std::uint64_t> samples(detail.levels.size()), sampled(detail.levels.size());
    std::vector<LevelStats> errors(detail.levels.size());  // rebuilt from the records
    for (std::size_t i = 0; i < detail.nodes.size(); ++i) {
        const NodeRecord& n = detail.nodes[i];
        ASSERT_LT(n.depth, detail.levels.size());
        rays_in[n.depth] += n.rays;
        ++nodes[n.depth];
        if (n.parent >= 0) {
            const NodeRecord& p = detail.nodes[std::size_t(n.parent)];
            EXPECT_EQ(p.depth + 1, n.depth);
            EXPECT_TRUE(p.children[0] == std::int32_t(i) || p.children[1] == std::int32_t(i) ||
                        p.second_early == std::int32_t(i));
        } else {
            EXPECT_EQ(n.depth, 0);
        }
        if (n.leaf) continue;
        ASSERT_EQ(n.candidates.size(), std::size_t(EdacrtParams{}.bins - 1));
        ASSERT_GE(n.chosen, 0);
        for (const CandidateSplit& c : n.candidates)
            EXPECT_GE(c.cost, n.candidates[std::size_t(n.chosen)].cost);
        const CandidateSplit& chosen = n.candidates[std::size_t(n.chosen)];
        EXPECT_EQ(chosen.left_triangles + chosen.right_triangles, n.triangles);
        // The defaults sample every split node, as node_sampling() says.
        const NodeSampling sampling = node_sampling(EdacrtParams{}, n.rays);
        EXPECT_EQ(n.alpha_source,
                  sampling.every_ray ? AlphaSource::every_ray : AlphaSource::sampled);
        EXPECT_EQ(n.samples, sampling.count);
        samples[n.depth] += n.samples;
        sampled[n.depth] += n.samples > 0;
        LevelStats& e = errors[n.depth];
        for (const double error : {n.alpha_error(0), n.alpha_error(1)}) {
            ++e.alpha_children;
            e.alpha_error_sum += error;
            e.add_alpha_error(error);
        }
    }
    for (std::size_t d = 0; d < detail.levels.size(); ++d) {
        const LevelStats& level = detail.levels[d];
        EXPECT_EQ(rays_in[d], level.rays_in) << "level " << d;
        EXPECT_EQ(nodes[d], level.nodes) << "level " << d;
        EXPECT_EQ(samples[d], level.sampled_rays) << "level " << d;
        EXPECT_EQ(sampled[d], level.sampled_nodes) << "level " << d;
        // The level's alpha error distribution is that of its recorded nodes' children.
        EXPECT_EQ(errors[d].alpha_children, level.alpha_children) << "level " << d;
        EXPECT_NEAR(errors[d].alpha_error_sum, level.alpha_error_sum, 1e-9) << "level " << d;
        EXPECT_EQ(errors[d].alpha_error_max, level.alpha_error_max) << "level " << d;
        EXPECT_TRUE(std::equal(std::begin(level.alpha_error_bins), std::end(level.alpha_error_bins),
                               std::begin(errors[d].alpha_error_bins)))
            << "level " << d;
    }

    // The followed ray: from the root down, depth first; it reaches the leaf of its hit.
    ASSERT_FALSE(detail.follow.empty());
    EXPECT_EQ(detail.follow.front().depth, 0);
    for (std::size_t k = 1; k < detail.follow.size(); ++k)
        EXPECT_LE(detail.follow[k].depth, detail.follow[k - 1].depth + 1);
    int hit_leaves = 0;
    for (const RayVisit& v : detail.follow) {
        ASSERT_GE(v.node, 0);
        const NodeRecord& n = detail.nodes[std::size_t(v.node)];
        EXPECT_EQ(n.leaf, v.leaf);
        hit_leaves += v.hit_here;
        if (v.hit_here) {
            EXPECT_TRUE(v.leaf);
        }
    }
    EXPECT_GE(hit_leaves, 1);
    std::uint16_t deepest = 0;
    for (const RayVisit& v : detail.follow) deepest = std::max(deepest, v.depth);
    EXPECT_EQ(deepest, detail.rays[followed].deepest_level);
}

/// scaled decides a node of 16-31 rays from a single ray (alpha 0 or 1); scaled-min tests
/// every ray of a node of at most sample_min rays (alpha exact) and draws at least sample_min
/// from larger ones, so its per-node alpha errors are much smaller.
TEST(TraceStats, ScaledMinAlphaErrorIsWellBelowScaled) {
    const Scene scene = make_builtin_scene("builtin:sphere:subdiv=5");
    const std::vector<Ray> rays =
        PinholeProjection(scene.camera.value_or(frame_box(scene.bounds())), 160, 120)
            .pixel_centre_rays();
    // The mean alpha error of the split nodes of at most `most` rays.
    const auto error = [&](SmallNodes policy, std::uint32_t most) {
        EdacrtParams p;
        p.small_nodes = policy;
        p.sample_min = 32;
        EdacrtTracer tracer(p);
        tracer.set_scene(scene);
        std::vector<Hit> hits(rays.size());
        TraceDetail detail;
        detail.max_nodes = 1'000'000;
        tracer.trace(rays, hits, Query::closest, &detail);
        double sum = 0.0;
        int children = 0;
        for (const NodeRecord& n : detail.nodes) {
            if (n.leaf || n.rays > most) continue;
            if (policy == SmallNodes::scaled_min) {
                EXPECT_EQ(n.alpha_source,
                          n.rays <= 32 ? AlphaSource::every_ray : AlphaSource::sampled);
                EXPECT_GE(n.samples, std::min(n.rays, 32u));
                if (n.rays <= 32) {
                    EXPECT_LT(std::max(n.alpha_error(0), n.alpha_error(1)), 1e-6);
                }
            }
            sum += n.alpha_error(0) + n.alpha_error(1);
            children += 2;
        }
        EXPECT_GT(children, 100);
        return sum / children;
    };
    for (const std::uint32_t most : {31u, 100u, 1000u}) {
        SCOPED_TRACE(most);
        EXPECT_LT(error(SmallNodes::scaled_min, most), 0.25 * error(SmallNodes::scaled, most));
    }
}

}  // namespace
}  // namespace edacrt
