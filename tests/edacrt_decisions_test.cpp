// The decisions of one EDACRT node, each on a constructed scene whose answer is known: filter
// skipping (Section 3.4), traversal order (3.3), the small-node sampling policy, the hit ratios
// (3.2), binning (3.1) and the leaf rules. The recorded root node (TraceDetail::nodes) shows
// what the recursion decided.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <functional>
#include <random>
#include <vector>

#include "scene/builtin_scenes.h"
#include "trace/edacrt_tracer.h"
#include "trace/presplit.h"
#include "util/error.h"

namespace edacrt {
namespace {

/// Adds a small triangle with its corners inside [lo, lo + 1]^3.
void add_small_triangle(Scene& scene, glm::vec3 lo, std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto base = std::uint32_t(scene.positions.size());
    const glm::vec3 corner = lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * 0.9f;
    scene.positions.push_back(corner);
    scene.positions.push_back(corner + glm::vec3(0.1f, 0.0f, 0.0f));
    scene.positions.push_back(corner + glm::vec3(0.0f, 0.1f, 0.05f));
    scene.triangles.push_back({base, base + 1, base + 2});
}

void add_triangle(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const auto base = std::uint32_t(scene.positions.size());
    scene.positions.insert(scene.positions.end(), {a, b, c});
    scene.triangles.push_back({base, base + 1, base + 2});
}

Scene finish(Scene scene) {
    scene.source = "constructed";
    scene.materials.resize(1);
    scene.triangle_materials.assign(scene.triangles.size(), 0);
    return scene;
}

/// Two clusters of 40 small triangles, in [0,1]^3 and [10,11] x [0,1]^2: every split of the
/// root separates them (the bins between them are empty).
Scene two_clusters() {
    Scene scene;
    std::mt19937 rng(3);
    for (int i = 0; i < 40; ++i) add_small_triangle(scene, {0, 0, 0}, rng);
    for (int i = 0; i < 40; ++i) add_small_triangle(scene, {10, 0, 0}, rng);
    return finish(std::move(scene));
}

/// Rays straight down (-z) from z = 5 through the left cluster's box (`left` of them) and the
/// right one's: each hits exactly one child box, so alpha_L = left / count exactly.
std::vector<Ray> down_rays(int left, int count) {
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        const float x = (i < left ? 0.2f : 10.2f) + 0.6f * float(i % 7) / 7.0f;
        rays.push_back({{x, 0.2f + 0.6f * float(i % 5) / 5.0f, 5.0f}, {0, 0, -1}});
    }
    return rays;
}

/// Rays along x through the clusters' y-z extent, from `x0` in direction `dx`.
std::vector<Ray> horizontal_rays(float x0, float dx, int count) {
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i)
        rays.push_back({{x0, 0.2f + 0.6f * float(i % 7) / 7.0f, 0.2f + 0.6f * float(i % 5) / 5.0f},
                        {dx, 0, 0}});
    return rays;
}

/// Parameters that make the root an inner node decided from every one of its rays.
EdacrtParams exact_root() {
    EdacrtParams p;
    p.presplit = 0.0f;  // the constructed triangles as they are
    p.leaf_rays = 1;
    p.leaf_tris = 16;
    p.cost_leaf_max_tris = 0;
    p.small_nodes = SmallNodes::every_ray;
    p.sample_threshold = 1000;
    return p;
}

/// Traces `rays` and returns the statistics with the root node recorded.
TraceDetail trace_root(const Scene& scene, const std::vector<Ray>& rays, const EdacrtParams& p) {
    EdacrtTracer tracer(p);
    tracer.set_scene(scene);
    std::vector<Hit> hits(rays.size());
    TraceDetail detail;
    detail.max_nodes = 1;
    tracer.trace(rays, hits, Query::closest, &detail);
    return detail;
}

const NodeRecord& root(const TraceDetail& detail) {
    EXPECT_EQ(detail.nodes.size(), 1u);
    return detail.nodes.at(0);
}

TEST(EdacrtDecisions, FilterSkippingFollowsEachRule) {
    const Scene scene = two_clusters();
    const std::vector<Ray> rays = down_rays(60, 100);  // alpha_L = 0.6, alpha_R = 0.4
    struct Case {
        const char* what;
        std::function<void(EdacrtParams&)> edit;
        bool skip_left, skip_right;
    };
    const Case cases[] = {
        // Inner children (40 triangles > leaf_tris): alpha > 1 - C_bv / (2 C_bv) = 1/2.
        {"paper, inner children", [](EdacrtParams&) {}, true, false},
        {"paper, inner children, C_bv = 30 (cancels)", [](EdacrtParams& p) { p.cost_filter = 30; },
         true, false},
        // Children that will be leaves by count: alpha > 1 - C_bv / (40 C_I) = 0.975...
        {"paper, leaf children", [](EdacrtParams& p) { p.leaf_tris = 40; }, false, false},
        // ...unless more rays than leaf_tris_rays would reach them: inner children again.
        {"paper, children of few triangles but many rays",
         [](EdacrtParams& p) {
             p.leaf_tris = 40;
             p.leaf_tris_rays = 99;
         },
         true, false},
        // ...or, with C_bv = 30, 0.25.
        {"paper, leaf children, C_bv = 30",
         [](EdacrtParams& p) {
             p.leaf_tris = 40;
             p.cost_filter = 30;
         },
         true, true},
        // The per-triangle rule prices every child as 40 C_child: 0.975, or 0.25 with C_bv 30.
        {"triangles", [](EdacrtParams& p) { p.filter_skip = FilterSkip::triangles; }, false, false},
        {"triangles, C_bv = 30",
         [](EdacrtParams& p) {
             p.filter_skip = FilterSkip::triangles;
             p.cost_filter = 30;
         },
         true, true},
        {"off", [](EdacrtParams& p) { p.filter_skip = FilterSkip::off; }, false, false},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        EdacrtParams p = exact_root();
        c.edit(p);
        const TraceDetail detail = trace_root(scene, rays, p);
        const NodeRecord& node = root(detail);
        ASSERT_FALSE(node.leaf);
        const CandidateSplit& chosen = node.candidates.at(std::size_t(node.chosen));
        ASSERT_EQ(chosen.left_triangles, 40u);
        EXPECT_FLOAT_EQ(chosen.alpha_left, 0.6f);
        EXPECT_FLOAT_EQ(chosen.alpha_right, 0.4f);
        EXPECT_EQ(node.filter_skipped[0], c.skip_left);
        EXPECT_EQ(node.filter_skipped[1], c.skip_right);
        // A skipped child gets all 100 rays; a filtered one those that hit its box.
        EXPECT_EQ(node.rays_passed[0], c.skip_left ? 100u : 60u);
        EXPECT_EQ(node.rays_passed[1], c.skip_right ? 100u : 40u);
    }
}

/// Near the root a first child whose alpha says skip is filtered all the same when the rays
/// its filter rejects (at least 512, and a fifth of the node's) make the second child's task:
/// on more than one thread, with the second child split, and not for a smaller missed part.
TEST(EdacrtDecisions, NearTheRootTheFirstChildIsFilteredForTheSecondChildsTask) {
    const Scene scene = two_clusters();
    struct Case {
        int left, count, threads;
        SecondChild second;
        bool skip_first;
    };
    const Case cases[] = {
        {1800, 2400, 1, SecondChild::split, true},        // one thread: no task
        {1800, 2400, 2, SecondChild::split, false},       // 600 missed rays: a task
        {1800, 2400, 2, SecondChild::after_first, true},  // no task is ever split off
        {1700, 2200, 2, SecondChild::split, true},        // 500 missed rays: too few
        {2450, 3000, 2, SecondChild::split, true},        // 550, but under a fifth
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::to_string(c.threads) + " threads, " + std::to_string(c.left) + " of " +
                     std::to_string(c.count) + " rays left");
        EdacrtParams p = exact_root();
        p.sample_threshold = 4000;
        p.second_child = c.second;
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                        std::size_t(c.threads));
        tbb::task_arena arena(c.threads);
        TraceDetail detail;
        arena.execute([&] { detail = trace_root(scene, down_rays(c.left, c.count), p); });
        const NodeRecord& node = root(detail);
        ASSERT_FALSE(node.leaf);
        ASSERT_TRUE(node.left_first);  // alpha_L = 0.75 to 0.82 > 1/2: skip by Section 3.4
        EXPECT_EQ(node.filter_skipped[0], c.skip_first);
        EXPECT_FALSE(node.filter_skipped[1]);
        EXPECT_EQ(node.rays_passed[0], std::uint32_t(c.skip_first ? c.count : c.left));
    }
}

TEST(EdacrtDecisions, TraversalOrderFollowsEachRule) {
    const Scene scene = two_clusters();
    struct Case {
        const char* what;
        std::vector<Ray> rays;
        TraversalOrder order;
        bool left_first;
    };
    const Case cases[] = {
        // From +x the right cluster is entered first; the direction sign agrees.
        {"from +x, sampled", horizontal_rays(20, -1, 50), TraversalOrder::sampled, false},
        {"from +x, sign", horizontal_rays(20, -1, 50), TraversalOrder::direction_sign, false},
        {"from -x, sampled", horizontal_rays(-10, 1, 50), TraversalOrder::sampled, true},
        // From between the clusters going +x only the right box is hit: sampling sees that, the
        // sign of the direction does not.
        {"from the gap, sampled", horizontal_rays(5, 1, 50), TraversalOrder::sampled, false},
        {"from the gap, sign", horizontal_rays(5, 1, 50), TraversalOrder::direction_sign, true},
        {"from +x, left-first", horizontal_rays(20, -1, 50), TraversalOrder::left_first, true},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        EdacrtParams p = exact_root();
        p.order = c.order;
        p.filter_skip = FilterSkip::off;
        const TraceDetail detail = trace_root(scene, c.rays, p);
        const NodeRecord& node = root(detail);
        ASSERT_FALSE(node.leaf);
        EXPECT_EQ(node.left_first, c.left_first);
    }
}

TEST(EdacrtDecisions, OrderQualityAndCullingCountWhatTheOrderBought) {
    // The left cluster and, at x = 10.5, a wall of 40 triangles that blocks every ray coming
    // from +x before it reaches the left cluster's box.
    Scene scene;
    std::mt19937 rng(3);
    for (int i = 0; i < 40; ++i) add_small_triangle(scene, {0, 0, 0}, rng);
    for (int i = 0; i < 20; ++i) {
        add_triangle(scene, {10.5f, -1, -1}, {10.5f, 2, -1}, {10.5f, 2, 2});
        add_triangle(scene, {10.5f, -1, -1}, {10.5f, 2, 2}, {10.5f, -1, 2});
    }
    scene = finish(std::move(scene));
    const std::vector<Ray> rays = horizontal_rays(20, -1, 50);
    for (const TraversalOrder order : {TraversalOrder::sampled, TraversalOrder::left_first}) {
        SCOPED_TRACE(order == TraversalOrder::sampled ? "sampled: the wall first" : "left first");
        EdacrtParams p = exact_root();
        p.order = order;
        p.filter_skip = FilterSkip::off;
        const TraceDetail detail = trace_root(scene, rays, p);
        ASSERT_FALSE(root(detail).leaf);
        const LevelStats& level = detail.levels.at(0);
        // Every ray hits both children's boxes and finds its hit in the wall.
        const bool wall_first = order == TraversalOrder::sampled;
        EXPECT_EQ(level.order_hits, wall_first ? 50u : 0u);
        EXPECT_EQ(level.order_misses, wall_first ? 0u : 50u);
        // Visiting the wall first culls all of them from the left cluster's filter.
        EXPECT_EQ(level.culled_by_distance, wall_first ? 50u : 0u);
    }
}

TEST(EdacrtDecisions, SmallNodesSampleByTheirPolicy) {
    const Scene scene = two_clusters();
    const std::vector<Ray> rays = down_rays(60, 100);
    const std::uint64_t tests_per_ray = 2 * (EdacrtParams{}.bins - 1);
    struct Case {
        SmallNodes policy;
        std::uint32_t threshold;
        std::uint64_t sampled;
    };
    const Case cases[] = {
        {SmallNodes::every_ray, 1000, 100},
        {SmallNodes::capped, 1000, 30},                        // at most sample_count
        {SmallNodes::surface_area, 1000, 0},                   // no sampling at all
        {SmallNodes::scaled, 1000, 100 / kScaledSampleShare},  // one in kScaledSampleShare
        {SmallNodes::scaled_min, 1000, 8},                     // at least sample_min = 8
        // Above the threshold every policy draws sample_count rays.
        {SmallNodes::every_ray, 50, 30},
        {SmallNodes::capped, 50, 30},
        {SmallNodes::surface_area, 50, 30},
        {SmallNodes::scaled, 50, 30},
        {SmallNodes::scaled_min, 50, 30},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::to_string(int(c.policy)) + " threshold " + std::to_string(c.threshold));
        EdacrtParams p = exact_root();
        p.small_nodes = c.policy;
        p.sample_threshold = c.threshold;
        p.sample_count = 30;
        p.sample_min = 8;
        const TraceDetail detail = trace_root(scene, rays, p);
        ASSERT_FALSE(detail.levels.empty());
        EXPECT_EQ(detail.levels[0].sampled_rays, c.sampled);
        EXPECT_EQ(detail.levels[0].sampled_nodes, c.sampled > 0 ? 1u : 0u);
        EXPECT_EQ(detail.levels[0].sample_box_tests, c.sampled * tests_per_ray);
        const NodeRecord& node = root(detail);
        EXPECT_EQ(node.samples, c.sampled);
        const AlphaSource source = c.sampled == 0     ? AlphaSource::area
                                   : c.sampled == 100 ? AlphaSource::every_ray
                                                      : AlphaSource::sampled;
        EXPECT_EQ(node.alpha_source, source);
        EXPECT_EQ(detail.levels[0].alpha_sources[int(source)], 1u);
        const CandidateSplit& chosen = node.candidates.at(std::size_t(node.chosen));
        if (c.sampled == 0) {  // surface-area ratios
            EXPECT_FLOAT_EQ(chosen.alpha_left,
                            chosen.left.surface_area() / node.box.surface_area());
        } else if (c.sampled == 100) {  // every ray: the exact ratio
            EXPECT_FLOAT_EQ(chosen.alpha_left, 0.6f);
        }
    }
}

TEST(EdacrtDecisions, ScaledMinSamplesAtLeastItsMinimumOrEveryRay) {
    EdacrtParams p;
    p.small_nodes = SmallNodes::scaled_min;
    p.sample_min = 32;
    p.sample_threshold = 1000;
    p.sample_count = 100;
    struct Case {
        std::size_t rays;
        std::uint32_t count;
        bool every_ray;
    };
    const Case cases[] = {
        {17, 17, true},     {32, 32, true},     // no more rays than the minimum: every one
        {33, 32, false},    {511, 32, false},   // one in 16 would be fewer: the minimum
        {512, 32, false},   {1000, 62, false},  // one in 16
        {1001, 100, false},                     // above the threshold: sample_count
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.rays);
        const NodeSampling s = node_sampling(p, c.rays);
        EXPECT_EQ(s.count, c.count);
        EXPECT_EQ(s.every_ray, c.every_ray);
    }
    // scaled draws a single ray for 17-31 rays; the other policies as before.
    p.small_nodes = SmallNodes::scaled;
    EXPECT_EQ(node_sampling(p, 17).count, 1u);
    EXPECT_EQ(node_sampling(p, 1000).count, 62u);
    p.small_nodes = SmallNodes::capped;
    EXPECT_FALSE(node_sampling(p, 500).every_ray);
    EXPECT_TRUE(node_sampling(p, 100).every_ray);
    p.small_nodes = SmallNodes::surface_area;
    EXPECT_EQ(node_sampling(p, 500).count, 0u);
}

TEST(EdacrtDecisions, SampledAlphaIsTheTrueAlphaWhenEveryRayIsSampled) {
    // At the root of the clusters...
    const TraceDetail clusters = trace_root(two_clusters(), down_rays(37, 90), exact_root());
    const NodeRecord& node = root(clusters);
    const CandidateSplit& chosen = node.candidates.at(std::size_t(node.chosen));
    EXPECT_FLOAT_EQ(chosen.alpha_left, node.alpha_true[0]);
    EXPECT_FLOAT_EQ(chosen.alpha_right, node.alpha_true[1]);

    // ...and in every node of a full recursion, where earlier hits have shortened the rays.
    const Scene soup = make_builtin_scene("builtin:soup:count=3000,seed=4,size=0.3");
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(-1.2f, 1.2f);
    std::vector<Ray> rays(20'000);
    for (Ray& ray : rays) ray = {{coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), 1}};
    EdacrtParams p;
    p.presplit = 0.0f;
    p.small_nodes = SmallNodes::every_ray;
    p.sample_threshold = 1'000'000;  // every node is small
    EdacrtTracer tracer(p);
    tracer.set_scene(soup);
    std::vector<Hit> hits(rays.size());
    TraceDetail detail;
    tracer.trace(rays, hits, Query::closest, &detail);
    std::uint64_t children = 0;
    for (const LevelStats& level : detail.levels) {
        children += level.alpha_children;
        EXPECT_NEAR(level.alpha_error_sum, 0.0, 1e-6 * double(level.alpha_children));
    }
    EXPECT_GT(children, 100u);
}

TEST(EdacrtDecisions, FarChildUnstoppedDropsTheRaysThatEnterTheFirstChildFirst) {
    // Every candidate that separates the clusters puts 40 triangles on each side, and every
    // ray hits both boxes (alpha_L = alpha_R = 1): the paper's cost is C_T + 80. Rays from -x
    // enter the left box first; from +x the right one. The order takes the left child first
    // (a tie goes left), so `unstopped` keeps in the right child's term only the rays from +x.
    const Scene scene = two_clusters();
    std::vector<Ray> half = horizontal_rays(-10, 1, 50);
    const std::vector<Ray> from_right = horizontal_rays(20, -1, 50);
    half.insert(half.end(), from_right.begin(), from_right.end());
    struct Case {
        const char* what;
        std::vector<Ray> rays;
        FarChild far_child;
        HitRatio hit_ratio;
        float cost;
    };
    const Case cases[] = {
        {"from -x, paper", horizontal_rays(-10, 1, 100), FarChild::paper, HitRatio::sampled, 82},
        {"from -x, unstopped", horizontal_rays(-10, 1, 100), FarChild::unstopped, HitRatio::sampled,
         42},
        {"both ways, paper", half, FarChild::paper, HitRatio::sampled, 82},
        {"both ways, unstopped", half, FarChild::unstopped, HitRatio::sampled, 62},
        // Area ratios have no sampled rays to drop: the switch changes nothing.
        {"area ratios, unstopped", horizontal_rays(-10, 1, 100), FarChild::unstopped,
         HitRatio::surface_area, -1},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        EdacrtParams p = exact_root();
        p.far_child = c.far_child;
        p.hit_ratio = c.hit_ratio;
        const NodeRecord node = root(trace_root(scene, c.rays, p));
        ASSERT_FALSE(node.leaf);
        EXPECT_TRUE(node.left_first);
        const CandidateSplit& chosen = node.candidates.at(std::size_t(node.chosen));
        EXPECT_EQ(chosen.left_triangles, 40u);
        EXPECT_EQ(chosen.right_triangles, 40u);
        if (c.hit_ratio == HitRatio::sampled) {
            // The hit ratios themselves (and with them filter skipping) stay the sampled ones.
            EXPECT_FLOAT_EQ(chosen.alpha_left, 1.0f);
            EXPECT_FLOAT_EQ(chosen.alpha_right, 1.0f);
            EXPECT_FLOAT_EQ(chosen.cost, c.cost);
        } else {
            p.far_child = FarChild::paper;
            const NodeRecord paper = root(trace_root(scene, c.rays, p));
            EXPECT_EQ(node.chosen, paper.chosen);
            EXPECT_FLOAT_EQ(chosen.cost, paper.candidates.at(std::size_t(paper.chosen)).cost);
        }
    }
}

TEST(EdacrtDecisions, LeavesByCountAndByCost) {
    const Scene scene = two_clusters();
    const std::vector<Ray> down = down_rays(60, 100);
    const auto leaf = [&](const std::vector<Ray>& rays, auto edit) {
        EdacrtParams p = exact_root();
        edit(p);
        return root(trace_root(scene, rays, p)).leaf;
    };
    EXPECT_FALSE(leaf(down, [](EdacrtParams&) {}));
    EXPECT_TRUE(leaf(down, [](EdacrtParams& p) { p.leaf_rays = 100; }));  // rays <= leaf_rays
    EXPECT_FALSE(leaf(down, [](EdacrtParams& p) { p.leaf_rays = 99; }));
    EXPECT_TRUE(leaf(down, [](EdacrtParams& p) { p.leaf_tris = 80; }));  // tris <= leaf_tris
    EXPECT_FALSE(leaf(down, [](EdacrtParams& p) { p.leaf_tris = 79; }));
    // ... reached by at most leaf_tris_rays rays (0: any number).
    const auto few_triangles = [](std::uint32_t rays) {
        return [rays](EdacrtParams& p) {
            p.leaf_tris = 80;
            p.leaf_tris_rays = rays;
        };
    };
    EXPECT_TRUE(leaf(down, few_triangles(100)));
    EXPECT_FALSE(leaf(down, few_triangles(99)));
    EXPECT_TRUE(leaf(down, few_triangles(0)));
    // Rays along x cross both clusters: alpha_L = alpha_R = 1, so a split costs C_T + 80 C_I,
    // more than the leaf's 80 C_I. Only the cost-based leaf (not in the paper) stops there.
    const std::vector<Ray> through = horizontal_rays(-10, 1, 50);
    EXPECT_TRUE(leaf(through, [](EdacrtParams& p) { p.cost_leaf_max_tris = 80; }));
    EXPECT_FALSE(leaf(through, [](EdacrtParams& p) { p.cost_leaf_max_tris = 79; }));
    EXPECT_FALSE(leaf(through, [](EdacrtParams& p) { p.cost_leaf_max_tris = 0; }));
}

TEST(EdacrtDecisions, FewTrianglesAreALeafOnlyForFewRays) {
    EdacrtParams p;  // leaves of 8 triangles for at most 256 rays
    ASSERT_EQ(p.leaf_tris, 8u);
    ASSERT_EQ(p.leaf_tris_rays, 256u);
    EXPECT_TRUE(triangle_leaf(p, 8, 256));
    EXPECT_FALSE(triangle_leaf(p, 8, 257));
    EXPECT_FALSE(triangle_leaf(p, 3, 1'000'000));
    EXPECT_FALSE(triangle_leaf(p, 9, 1));
    // Two triangles are never worth a split (two box tests to spare one triangle test).
    EXPECT_TRUE(triangle_leaf(p, kAlwaysLeafTris, 1'000'000));
    EXPECT_TRUE(triangle_leaf(p, 0, 1'000'000));
    p.leaf_tris = 1;  // ...unless leaf-tris asks for smaller leaves
    EXPECT_FALSE(triangle_leaf(p, 2, 1));
    EXPECT_TRUE(triangle_leaf(p, 1, 1'000'000));
    p.leaf_tris = 8;
    p.leaf_tris_rays = 0;  // the paper: whatever the rays
    EXPECT_TRUE(triangle_leaf(p, 8, 1'000'000));
    EXPECT_FALSE(triangle_leaf(p, 9, 1));
    const EdacrtParams paper = paper_params();
    EXPECT_EQ(paper.leaf_tris_rays, 0u);
    EXPECT_EQ(paper.leaf_tris, 4u);
}

TEST(EdacrtDecisions, BinsSpanTheNodeBoxOrTheCentroids) {
    // Ten small triangles with centroids near x = 0.5 .. 9.5 and one long one to x = 80.
    Scene scene;
    for (int i = 0; i < 10; ++i)
        add_triangle(scene, {float(i) + 0.4f, 0, 0}, {float(i) + 0.6f, 0, 0},
                     {float(i) + 0.5f, 0.2f, 0});
    add_triangle(scene, {0, 0, 0.5f}, {80, 0, 0.5f}, {0.8f, 0.3f, 0.5f});
    scene = finish(std::move(scene));
    std::vector<Ray> rays = horizontal_rays(-10, 1, 40);
    EdacrtParams p = exact_root();
    p.leaf_tris = 1;
    p.binning = Binning::node_box;  // bins 10 wide: the ten small ones share bin 0
    EXPECT_EQ(root(trace_root(scene, rays, p)).candidates.at(0).left_triangles, 10u);
    p.binning = Binning::centroids;  // bins over [0.5, 26.9], 3.3 wide: four in bin 0
    EXPECT_EQ(root(trace_root(scene, rays, p)).candidates.at(0).left_triangles, 4u);

    // Centroids that all fall into one bin of the node box: binning falls back to their range.
    Scene wide;
    add_triangle(wide, {-100, 0, 0}, {100, 0, 0}, {0, 1, 0});
    for (int i = 0; i < 20; ++i)
        add_triangle(wide, {0.01f * float(i), 0, 0}, {0.01f * float(i) + 0.005f, 0, 0},
                     {0.01f * float(i), 0.01f, 0});
    wide = finish(std::move(wide));
    std::vector<Ray> down;
    for (int i = 0; i < 40; ++i) down.push_back({{0.005f * float(i), 0.001f, 1}, {0, 0, -1}});
    p.binning = Binning::node_box;
    EXPECT_FALSE(root(trace_root(wide, down, p)).leaf);
}

TEST(EdacrtPresplit, PiecesKeepTheHitsAndFollowTheParameter) {
    // The Cornell box's walls and floor are a few large triangles: the ones pieces help.
    const Scene scene = make_builtin_scene("builtin:cornell");
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
    const Aabb box = scene.bounds();
    std::vector<Ray> rays(20'000);
    for (Ray& ray : rays) {
        const glm::vec3 u(0.5f + 0.5f * coord(rng), 0.5f + 0.5f * coord(rng),
                          0.5f + 0.5f * coord(rng));
        ray = {box.lo + u * (box.hi - box.lo), {coord(rng), coord(rng), coord(rng)}};
        if (ray.dir == glm::vec3(0.0f)) ray.dir = {0, 0, 1};
    }
    const auto naive = make_tracer(Method::naive);
    naive->set_scene(scene);
    std::vector<Hit> expected(rays.size()), hits(rays.size());
    naive->trace(rays, expected, Query::closest);
    EdacrtParams p;
    p.presplit = 0.0f;
    EdacrtTracer tracer(p);
    tracer.set_scene(scene);
    std::vector<std::uint64_t> counts;
    for (const float extra : {0.0f, 0.3f, 2.0f, 8.0f}) {
        p.presplit = extra;
        tracer.set_params(p);  // after set_scene: the pieces follow
        TraceDetail detail;
        tracer.trace(rays, hits, Query::closest, &detail);
        // The root holds the pieces: at most `extra` per triangle more, only for triangles
        // whose box is at least twice the mean (the walls, floor and ceiling).
        const std::uint64_t pieces = detail.levels.at(0).triangles, n = scene.triangle_count();
        counts.push_back(pieces);
        if (extra == 0.0f) {
            EXPECT_EQ(pieces, n);
        }
        EXPECT_LE(double(pieces), double(n) * (1.0 + extra) + 1.0) << extra;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            // The same distance; a tie at a shared edge may name the other triangle.
            ASSERT_EQ(hits[i].t, expected[i].t) << "presplit " << extra << ", ray " << i;
            ASSERT_EQ(hits[i].hit(), expected[i].hit());
            ASSERT_LT(hits[i].prim, std::int32_t(scene.triangle_count()));
        }
    }
    // 0.3 is 9 pieces here, too few to cut a wall in proportion; 2 cuts the large ones.
    EXPECT_GE(counts[1], counts[0]);
    EXPECT_GT(counts[2], counts[1]);
    EXPECT_GT(counts[2], counts[0] + counts[0] / 4);
    EXPECT_GE(counts[3], counts[2]);
    p.presplit = 8.5f;
    EXPECT_THROW(tracer.set_params(p), InputError);
    p.presplit = -0.1f;
    EXPECT_THROW(tracer.set_params(p), InputError);
}

// A mesh of alike triangles (no box twice the mean) is not cut: pieces there only make nodes
// hold more references (the bunny: 10 ms per frame, 2-5% more triangle tests); one triangle
// far larger than the rest is.
TEST(EdacrtPresplit, OnlyTrianglesMuchLargerThanTheMeanAreCut) {
    std::vector<Triangle> alike;
    for (int i = 0; i < 100; ++i) {
        const float x = float(i % 10), y = float(i / 10);
        alike.push_back({{x, y, 0}, {x + 1, y, 0}, {x, y + 1 + 0.01f * float(i % 7), 0.5f}});
    }
    const auto plan = [](const std::vector<Triangle>& triangles, float extra) {
        std::vector<float> areas;
        Aabb grid;
        for (const Triangle& tri : triangles) {
            areas.push_back(box_area(corners_bounds(tri)));
            grid.extend(corners_bounds(tri));
        }
        return plan_presplit(areas, extra, grid);
    };
    EXPECT_TRUE(plan(alike, 0.3f).cut.empty());  // no triangle cut
    EXPECT_TRUE(plan(alike, 8.0f).cut.empty());
    std::vector<Triangle> one_large = alike;
    one_large.push_back({{0, 0, -1}, {40, 0, -1}, {0, 40, 5}});
    const PresplitPlan large = plan(one_large, 0.3f);
    ASSERT_EQ(large.cut, std::vector<std::uint32_t>{std::uint32_t(alike.size())});
    EXPECT_EQ(large.pieces, std::vector<std::uint32_t>{31u});  // the budget, all to the large one
    EXPECT_EQ(large.grid.lo, glm::vec3(0, 0, -1));
}

// A box whose area overflows, or is NaN, counts as no area: it is never cut, and it does not
// make every other box look small.
TEST(EdacrtPresplit, AreasThatOverflowAreNotCut) {
    const Triangle huge{{-3e38f, -3e38f, 0}, {3e38f, -3e38f, 0}, {0, 3e38f, 1}};
    EXPECT_EQ(box_area(corners_bounds(huge)), 0.0f);
    std::vector<float> areas(100, 1.0f);
    areas.push_back(box_area(corners_bounds(huge)));
    areas.push_back(50.0f);
    const PresplitPlan plan = plan_presplit(areas, 0.2f, Aabb{glm::vec3(0), glm::vec3(1)});
    ASSERT_EQ(plan.cut, std::vector<std::uint32_t>{101u});
    // An extra piece per twice the mean area (150 / 102): 17, within the budget of 20.
    EXPECT_EQ(plan.pieces, std::vector<std::uint32_t>{18u});
}

// Every point of a cut triangle lies in one of its pieces' boxes, each box lies in the whole
// triangle's conservative box, and together they reach its every side: on walls, slivers, far
// and tiny triangles, and ones the grid cuts at their corners.
TEST(EdacrtPresplit, PiecesCoverTheTriangle) {
    const Aabb grid{{-1e3f, -1e3f, -1e3f}, {1e3f, 1e3f, 1e3f}};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto contains = [](const Aabb& box, const glm::vec3& p) {
        return glm::all(glm::lessThanEqual(box.lo, p)) && glm::all(glm::lessThanEqual(p, box.hi));
    };
    const std::vector<Triangle> triangles = {
        {{-900, -900, 0}, {900, -900, 0}, {-900, 900, 0}},             // a floor
        {{-1e3f, 0, 0}, {1e3f, 1e-3f, 0}, {1e3f, 0, 1e-3f}},           // a sliver
        {{999, 999, 999}, {999.001f, 999, 999}, {999, 999.2f, 1000}},  // far and small
        {{0, 0, 0}, {500, 500, 500}, {250, 0, 500}},                   // corners on grid planes
        {{-3, 7, 1}, {400, -200, 31}, {17, 350, -600}},                // oblique
    };
    for (const Triangle& tri : triangles) {
        for (const std::size_t count : {2u, 3u, 7u, 64u}) {
            SCOPED_TRACE(testing::Message() << count << " pieces");
            std::vector<Aabb> pieces(count);
            const std::size_t made = split_triangle(tri, grid, pieces);
            ASSERT_GE(made, 1u);
            ASSERT_LE(made, count);
            const Aabb whole = conservative_bounds(tri);
            Aabb all;
            for (std::size_t k = 0; k < made; ++k) {
                EXPECT_TRUE(contains(whole, pieces[k].lo) && contains(whole, pieces[k].hi));
                all.extend(pieces[k]);
            }
            EXPECT_EQ(all.lo, whole.lo);
            EXPECT_EQ(all.hi, whole.hi);
            for (int i = 0; i < 2000; ++i) {
                float u = unit(rng), v = unit(rng);
                if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
                const glm::vec3 p = tri.p0 + u * (tri.p1 - tri.p0) + v * (tri.p2 - tri.p0);
                bool inside = false;
                for (std::size_t k = 0; k < made && !inside; ++k) inside = contains(pieces[k], p);
                ASSERT_TRUE(inside) << "point " << i;
            }
        }
    }
}

TEST(EdacrtPresets, PaperAndDacrtSetTheirChoices) {
    const EdacrtParams paper = preset_params("paper");
    EXPECT_EQ(paper, paper_params());
    EXPECT_EQ(paper.binning, Binning::node_box);
    EXPECT_EQ(paper.filter_skip, FilterSkip::paper);
    EXPECT_EQ(paper.small_nodes, SmallNodes::every_ray);
    EXPECT_EQ(paper.cost_leaf_max_tris, 0u);
    EXPECT_EQ(paper.sample_threshold, 1000u);
    EXPECT_EQ(paper.sample_count, 100u);
    EXPECT_EQ(paper.far_child, FarChild::paper);
    const EdacrtParams dacrt = preset_params("dacrt");
    EXPECT_EQ(dacrt.hit_ratio, HitRatio::surface_area);
    EXPECT_EQ(dacrt.order, TraversalOrder::direction_sign);
    EXPECT_EQ(dacrt.filter_skip, FilterSkip::off);
    EXPECT_EQ(preset_params("default"), EdacrtParams{});
    EXPECT_THROW(preset_params("fast"), InputError);
}

TEST(EdacrtParamInfo, EveryParameterParsesPrintsAndRejects) {
    EdacrtParams p;
    EXPECT_EQ(edacrt_param_info().size(), 21u);
    for (const ParamInfo& info : edacrt_param_info()) {
        SCOPED_TRACE(std::string(info.key));
        EXPECT_EQ(find_param(info.key), &info);
        EXPECT_FALSE(info.help.empty());
        // Its own text reads back to the same value.
        EdacrtParams copy = p;
        set_param(copy, info, param_text(p, info));
        EXPECT_EQ(copy, p);
        EXPECT_THROW(set_param(copy, info, "nonsense"), InputError);
        EXPECT_THROW(set_param(copy, info, ""), InputError);
        if (info.kind == ParamInfo::Kind::choice) {
            for (std::string_view name : info.choices) {
                set_param(copy, info, name);
                EXPECT_EQ(param_text(copy, info), name);
                validate(copy);
            }
        } else {
            EXPECT_THROW(set_param(copy, info, "nan"), InputError);
            EXPECT_THROW(set_param(copy, info, "inf"), InputError);
            EXPECT_THROW(set_param(copy, info, std::to_string(info.max * 2 + 1)), InputError);
            EXPECT_THROW(set_param(copy, info, std::to_string(info.min - 1)), InputError);
            if (info.kind == ParamInfo::Kind::integer) {
                EXPECT_THROW(set_param(copy, info, "2.5"), InputError);
            }
        }
    }
    EXPECT_EQ(find_param("no-such-parameter"), nullptr);
    // An enum value out of range (a corrupted struct) is caught by validate().
    EdacrtParams bad;
    bad.order = TraversalOrder(7);
    EXPECT_THROW(validate(bad), InputError);
}

}  // namespace
}  // namespace edacrt
