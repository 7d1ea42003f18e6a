// Every method traces a batch with 4 engine threads exactly as with 1, and EDACRT's recursion
// (with its statistics) is the same for 1, 2 and 8. A binary of its own, so
// that the ThreadSanitizer build of scripts/test compiles and runs just this (and the viewer's
// worker) to look for races inside the tracers.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "sanitizers.h"
#include "scene/builtin_scenes.h"
#include "scene/camera.h"
#include "trace/edacrt_params.h"
#include "trace/tracer.h"

namespace edacrt {
namespace {

/// Rays from random points of the soup's box in random directions, some of them short.
std::vector<Ray> random_rays(std::size_t count) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coord(-1.2f, 1.2f);
    std::vector<Ray> rays(count);
    for (Ray& ray : rays) {
        ray.org = {coord(rng), coord(rng), coord(rng)};
        do ray.dir = {coord(rng), coord(rng), coord(rng)};
        while (ray.dir == glm::vec3(0.0f));
        if (rng() % 4 == 0) ray.tmax = 0.3f;
    }
    return rays;
}

/// Pixel-centre camera rays framing `scene` at size x size pixels, then `random` random rays.
std::vector<Ray> camera_and_random_rays(const Scene& scene, int size, std::size_t random) {
    std::vector<Ray> rays =
        PinholeProjection(frame_box(scene.bounds()), size, size).pixel_centre_rays();
    const std::vector<Ray> more = random_rays(random);
    rays.insert(rays.end(), more.begin(), more.end());
    return rays;
}

/// Traces in an arena of `threads` slots (more than this machine's cores is fine: the point is
/// concurrent access, which ThreadSanitizer checks).
std::vector<Hit> trace(Tracer& tracer, const std::vector<Ray>& rays, Query query, int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    std::size_t(threads));
    tbb::task_arena arena(threads);
    std::vector<Hit> hits(rays.size());
    arena.execute([&] {
        EXPECT_EQ(tbb::this_task_arena::max_concurrency(), threads);
        tracer.trace(rays, hits, query);
    });
    return hits;
}

class TracerThreads : public ::testing::TestWithParam<Method> {};

TEST_P(TracerThreads, FourThreadsTraceAsOne) {
    // A soup: no shared edges, so no ties whose winner could depend on the order.
    const Scene scene = make_builtin_scene("builtin:soup:count=200,seed=3,size=0.4");
    const std::vector<Ray> rays = random_rays(50'000);
    const auto tracer = make_tracer(GetParam());
    tracer->set_scene(scene);
    for (Query query : {Query::closest, Query::any}) {
        const std::vector<Hit> one = trace(*tracer, rays, query, 1);
        const std::vector<Hit> four = trace(*tracer, rays, query, 4);
        std::size_t hits = 0, differences = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            hits += one[i].hit();
            // Any-hit may stop at a different occluder; whether there is one is fixed.
            const bool same = query == Query::any
                                  ? one[i].hit() == four[i].hit()
                                  : one[i].prim == four[i].prim && one[i].t == four[i].t &&
                                        one[i].u == four[i].u && one[i].v == four[i].v;
            if (!same && ++differences <= 5)
                ADD_FAILURE() << "ray " << i << ": prim " << one[i].prim << " t " << one[i].t
                              << " with 1 thread, prim " << four[i].prim << " t " << four[i].t
                              << " with 4";
        }
        EXPECT_EQ(differences, 0u) << (query == Query::any ? "any hit" : "closest hit");
        EXPECT_GT(hits, rays.size() / 10) << "the batch exercises hits";
        EXPECT_LT(hits, rays.size()) << "and misses";
    }
}

/// A batch traced with statistics and recordings in an arena of `threads` slots.
struct Traced {
    std::vector<Hit> hits;
    TraceStats totals;
    TraceDetail detail;
};

Traced trace_detailed(Tracer& tracer, const std::vector<Ray>& rays, Query query, int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    std::size_t(threads));
    tbb::task_arena arena(threads);
    Traced out;
    out.hits.resize(rays.size());
    out.detail.max_nodes = 2000;
    out.detail.follow_ray = std::int64_t(rays.size() / 2);
    arena.execute([&] {
        std::vector<Hit> fast(rays.size());
        out.totals = tracer.trace(rays, fast, query);
        tracer.trace(rays, out.hits, query, &out.detail);
        EXPECT_EQ(std::memcmp(fast.data(), out.hits.data(), fast.size() * sizeof(Hit)), 0);
    });
    return out;
}

/// Everything but the timings.
void expect_same(const Traced& a, const Traced& b) {
    ASSERT_EQ(a.hits.size(), b.hits.size());
    EXPECT_EQ(std::memcmp(a.hits.data(), b.hits.data(), a.hits.size() * sizeof(Hit)), 0);
    EXPECT_EQ(a.totals.ray_box_tests, b.totals.ray_box_tests);
    EXPECT_EQ(a.totals.ray_triangle_tests, b.totals.ray_triangle_tests);
    const TraceDetail &x = a.detail, &y = b.detail;
    EXPECT_EQ(x.root.entered, y.root.entered);
    ASSERT_EQ(x.levels.size(), y.levels.size());
    for (std::size_t d = 0; d < x.levels.size(); ++d) {
        LevelStats l = x.levels[d], m = y.levels[d];
        for (double* t : {l.phase_seconds, m.phase_seconds}) std::fill_n(t, 4, 0.0);
        EXPECT_EQ(std::memcmp(&l, &m, sizeof l), 0) << "level " << d;
    }
    ASSERT_EQ(x.rays.size(), y.rays.size());
    EXPECT_EQ(std::memcmp(x.rays.data(), y.rays.data(), x.rays.size() * sizeof(RayStats)), 0);
    ASSERT_EQ(x.nodes.size(), y.nodes.size());
    for (std::size_t i = 0; i < x.nodes.size(); ++i) {
        const NodeRecord &n = x.nodes[i], &o = y.nodes[i];
        EXPECT_TRUE(n.parent == o.parent && n.children[0] == o.children[0] &&
                    n.children[1] == o.children[1] && n.depth == o.depth && n.box.lo == o.box.lo &&
                    n.box.hi == o.box.hi && n.rays == o.rays && n.triangles == o.triangles &&
                    n.leaf == o.leaf && n.axis == o.axis && n.chosen == o.chosen &&
                    n.left_first == o.left_first && n.filter_skipped[0] == o.filter_skipped[0] &&
                    n.filter_skipped[1] == o.filter_skipped[1] &&
                    n.rays_passed[0] == o.rays_passed[0] && n.rays_passed[1] == o.rays_passed[1] &&
                    n.alpha_true[0] == o.alpha_true[0] && n.alpha_true[1] == o.alpha_true[1] &&
                    n.candidates.size() == o.candidates.size())
            << "node " << i;
        for (std::size_t c = 0; c < std::min(n.candidates.size(), o.candidates.size()); ++c)
            EXPECT_EQ(std::memcmp(&n.candidates[c], &o.candidates[c], sizeof(CandidateSplit)), 0)
                << "node " << i << " candidate " << c;
    }
    ASSERT_EQ(x.follow.size(), y.follow.size());
    for (std::size_t i = 0; i < x.follow.size(); ++i)
        EXPECT_TRUE(x.follow[i].node == y.follow[i].node &&
                    x.follow[i].passed[0] == y.follow[i].passed[0] &&
                    x.follow[i].passed[1] == y.follow[i].passed[1] &&
                    x.follow[i].hit_here == y.follow[i].hit_here)
            << "visit " << i;
}

/// One recursion per batch: hits (any-hit occluders too), counters, per-level and per-ray
/// statistics and the recorded nodes are the same for 2, 4 and 8 threads; on 1 thread, where no
/// task can run beside the first child, `--second-child split` is the recursion of
/// `after-first` (so, with the paper preset's after-first, 1 thread is the same as any). The
/// batch and the mesh are large enough for every parallel step (partitions and binning of
/// >= 8192 items, large leaves), and the sphere's shared edges make ties whose winner depends
/// on the order.
TEST(EdacrtThreads, TheRecursionIsTheSameForAnyThreadCountAndAfterFirstOnOne) {
    const Scene scene = make_builtin_scene("builtin:sphere:subdiv=5");
    const std::vector<Ray> rays = camera_and_random_rays(scene, 300, 20'000);
    ASSERT_GE(rays.size(), 100'000u);
    for (const EdacrtParams& p : {EdacrtParams{}, paper_params(), dacrt_params()}) {
        EdacrtParams after_first = p;
        after_first.second_child = SecondChild::after_first;
        const auto tracer = make_tracer(Method::edacrt, p);
        const auto waiting = make_tracer(Method::edacrt, after_first);
        tracer->set_scene(scene);
        waiting->set_scene(scene);
        for (Query query : {Query::closest, Query::any}) {
            SCOPED_TRACE(query == Query::any ? "any hit" : "closest hit");
            const Traced two = trace_detailed(*tracer, rays, query, 2);
            EXPECT_EQ(two.detail.levels.at(0).nodes, 1u);
            EXPECT_GT(two.detail.nodes.size(), 100u);
            SCOPED_TRACE("4 threads");
            expect_same(two, trace_detailed(*tracer, rays, query, 4));
            // The sanitizers look for races and memory errors, which 2 and 4 threads show;
            // the rest is the same code on other counts (ThreadSanitizer: 128 s for all).
            if (test::kSanitized) continue;
            SCOPED_TRACE("8 threads");
            expect_same(two, trace_detailed(*tracer, rays, query, 8));
            SCOPED_TRACE("1 thread against after-first on 2");
            expect_same(trace_detailed(*waiting, rays, query, 2),
                        trace_detailed(*tracer, rays, query, 1));
        }
    }
}

/// Speculation: with few rays over many triangles, second children run beside first ones on
/// copies of the rays (the statistics count those nodes); the statistics run, which takes the
/// children in turn, finds the same hits, counters and statistics, on 2 threads as on 4, and
/// each ray the distance the paper's order finds (after-first; a tie may name another
/// triangle at that distance).
TEST(EdacrtThreads, SpeculationKeepsThePapersHitsAndItsStatisticsRun) {
    const Scene scene = make_builtin_scene("builtin:sphere:subdiv=6");
    const std::vector<Ray> rays = camera_and_random_rays(scene, 100, 5'000);
    EdacrtParams after_first;
    after_first.second_child = SecondChild::after_first;
    const auto tracer = make_tracer(Method::edacrt);
    const auto waiting = make_tracer(Method::edacrt, after_first);
    tracer->set_scene(scene);
    waiting->set_scene(scene);
    const Traced two = trace_detailed(*tracer, rays, Query::closest, 2);
    std::uint64_t speculated = 0;
    for (const LevelStats& level : two.detail.levels) speculated += level.speculated;
    EXPECT_GT(speculated, 0u) << "no node speculated";
    TraceStats detailed;  // the statistics run's counters are the fast run's
    for (const LevelStats& level : two.detail.levels) {
        detailed.ray_box_tests += level.ray_box_tests;
        detailed.ray_triangle_tests += level.ray_triangle_tests;
    }
    EXPECT_EQ(detailed.ray_box_tests + two.detail.root.box_tests, two.totals.ray_box_tests);
    EXPECT_EQ(detailed.ray_triangle_tests, two.totals.ray_triangle_tests);
    SCOPED_TRACE("4 threads");
    expect_same(two, trace_detailed(*tracer, rays, Query::closest, 4));
    const Traced paper = trace_detailed(*waiting, rays, Query::closest, 2);
    std::size_t hits = 0, ties = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits += paper.hits[i].hit();
        ASSERT_EQ(two.hits[i].t, paper.hits[i].t) << "ray " << i;
        ties += two.hits[i].prim != paper.hits[i].prim;
    }
    EXPECT_GT(hits, rays.size() / 4);
    EXPECT_LT(ties, rays.size() / 100);
}

std::vector<Method> methods() {
    std::vector<Method> out = {Method::naive, Method::edacrt, Method::dacrt, Method::bvh};
#ifdef EDACRT_HAS_EMBREE
    out.push_back(Method::embree);
#endif
    return out;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, TracerThreads, ::testing::ValuesIn(methods()),
                         [](const auto& info) {
                             return std::string(enum_name(kMethods, info.param));
                         });

}  // namespace
}  // namespace edacrt
