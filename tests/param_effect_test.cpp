// param_no_effect_reason(): which parameters the switches make inert, for every parameter and
// the switches that decide it; and the honest check, that a parameter reported inert changes
// neither a hit nor a counter of a real trace, whatever its value.
#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <cstring>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "scene/obj_loader.h"
#include "test_paths.h"
#include "trace/edacrt_tracer.h"
#include "util/error.h"

namespace edacrt {
namespace {

using Keys = std::set<std::string>;

/// The keys of the parameters reported inert.
Keys inert(const EdacrtParams& p, int threads) {
    Keys keys;
    for (const ParamInfo& info : edacrt_param_info()) {
        const auto reason = param_no_effect_reason(p, info, threads);
        if (reason) {
            EXPECT_FALSE(reason->empty()) << info.key;
            keys.emplace(info.key);
        }
    }
    return keys;
}

EdacrtParams with(std::function<void(EdacrtParams&)> change, EdacrtParams p = {}) {
    change(p);
    return p;
}

const Keys kSampling = {"sample-threshold", "sample-count", "small-nodes", "sample-min",
                        "sampling-seed"};

TEST(ParamNoEffect, EachParameterUnderTheSwitchesThatDecideIt) {
    // Defaults: C_T cancels out of the split choice without the cost leaf, C_child is for
    // filter-skip=triangles only; split second children need a second thread.
    EXPECT_EQ(inert({}, 4), (Keys{"c-t", "c-child"}));
    EXPECT_EQ(inert({}, 1), (Keys{"c-t", "c-child", "second-child"}));
    // The paper samples every ray of small nodes: no minimum.
    EXPECT_EQ(inert(paper_params(), 4), (Keys{"c-t", "c-child", "sample-min"}));
    // DACRT samples nothing and always filters.
    Keys dacrt = kSampling;
    dacrt.insert({"c-t", "c-i", "c-bv", "c-child", "far-child"});
    EXPECT_EQ(inert(dacrt_params(), 4), dacrt);
    // Sampling is on when either the hit ratio or the order is sampled.
    // Area ratios leave the far child's term as it is.
    EXPECT_EQ(inert(with([](auto& p) { p.hit_ratio = HitRatio::surface_area; }), 4),
              (Keys{"c-t", "c-child", "far-child"}));
    EXPECT_EQ(inert(with([](auto& p) { p.order = TraversalOrder::left_first; }), 4),
              (Keys{"c-t", "c-child"}));
    // The cost leaf takes C_T and C_I, if it reaches above the nodes that are leaves whatever
    // their rays: with leaf-tris rays, nodes of 3..leaf_tris triangles that many rays reach
    // choose a split, and the cost leaf is tested there.
    EXPECT_EQ(inert(with([](auto& p) { p.cost_leaf_max_tris = 64; }), 4), (Keys{"c-child"}));
    EXPECT_EQ(inert(with([](auto& p) { p.cost_leaf_max_tris = p.leaf_tris; }), 4),
              (Keys{"c-child"}));
    EXPECT_EQ(inert(with([](auto& p) { p.cost_leaf_max_tris = kAlwaysLeafTris; }), 4),
              (Keys{"c-t", "c-child"}));
    EXPECT_EQ(inert(with([](auto& p) {
                        p.cost_leaf_max_tris = p.leaf_tris;
                        p.leaf_tris_rays = 0;
                    }),
                    4),
              (Keys{"c-t", "c-child"}));
    // Leaves of at most 2 triangles are leaves whatever their rays.
    EXPECT_EQ(inert(with([](auto& p) { p.leaf_tris = kAlwaysLeafTris; }), 4),
              (Keys{"c-t", "c-child", "leaf-tris-rays"}));
    // filter-skip=triangles prices by C_child, not C_I.
    EXPECT_EQ(inert(with([](auto& p) { p.filter_skip = FilterSkip::triangles; }), 4),
              (Keys{"c-t", "c-i"}));
    // Free filtering is never skipped.
    EXPECT_EQ(inert(with([](auto& p) { p.cost_filter = 0.0f; }), 4),
              (Keys{"c-t", "c-i", "c-child", "filter-skip"}));
    EXPECT_EQ(inert(with([](auto& p) {
                        p.filter_skip = FilterSkip::triangles;
                        p.cost_filter = 0.0f;
                    }),
                    4),
              (Keys{"c-t", "c-i", "c-child", "filter-skip"}));
    // No small node samples when the small ones are all leaves.
    EXPECT_EQ(inert(with([](auto& p) { p.sample_threshold = 16; }), 4),
              (Keys{"c-t", "c-child", "small-nodes", "sample-min"}));
    // Small nodes that draw as large ones do make the threshold inert.
    EXPECT_EQ(inert(with([](auto& p) {
                        p.small_nodes = SmallNodes::capped;
                        p.sample_count = 16;
                    }),
                    4),
              (Keys{"c-t", "c-child", "sample-threshold", "sample-min"}));
    EXPECT_EQ(inert(with([](auto& p) {
                        p.small_nodes = SmallNodes::capped;
                        p.sample_count = 17;
                    }),
                    4),
              (Keys{"c-t", "c-child", "sample-min"}));
    EXPECT_EQ(inert(with([](auto& p) {
                        p.small_nodes = SmallNodes::scaled;
                        p.sample_count = 1;  // 16 rays per sample, and nodes of 17 rays sample
                    }),
                    4),
              (Keys{"c-t", "c-child", "sample-threshold", "sample-min"}));
    EXPECT_EQ(inert(with([](auto& p) {
                        p.small_nodes = SmallNodes::scaled;
                        p.sample_count = 2;
                    }),
                    4),
              (Keys{"c-t", "c-child", "sample-min"}));
    // Whatever the switches, these always matter.
    for (const EdacrtParams& p : {EdacrtParams{}, paper_params(), dacrt_params()})
        for (const char* key : {"bins", "binning", "hit-ratio", "order", "leaf-rays", "leaf-tris",
                                "cost-leaf-max-tris", "presplit"})
            EXPECT_FALSE(param_no_effect_reason(p, *find_param(key), 1)) << key;
}

/// What a trace produced: its hits and every counter (statistics' times left out).
struct Outcome {
    std::vector<Hit> hits;
    TraceStats totals;
    std::vector<std::vector<double>> levels;
};

Outcome trace(const Scene& scene, const std::vector<Ray>& rays, const EdacrtParams& p,
              int threads) {
    Outcome out;
    out.hits.resize(rays.size());
    TraceDetail detail;
    tbb::task_arena(threads).execute([&] {
        EdacrtTracer tracer(p);
        tracer.set_scene(scene);
        out.totals = tracer.trace(rays, out.hits, Query::closest, &detail);
    });
    for (const LevelStats& l : detail.levels)
        out.levels.push_back(
            {double(l.nodes), double(l.leaves), double(l.rays_in), double(l.rays_passed),
             double(l.filters_done), double(l.filters_skipped), double(l.second_splits),
             double(l.triangles), double(l.sample_box_tests), double(l.filter_box_tests),
             double(l.ray_triangle_tests), double(l.sampled_rays), double(l.candidate_splits),
             double(l.order_hits), double(l.order_misses), double(l.culled_by_distance),
             l.alpha_estimated_sum, l.alpha_true_sum});
    return out;
}

/// Values across the parameter's range (every choice).
std::vector<double> values(const ParamInfo& info) {
    if (info.kind == ParamInfo::Kind::choice) {
        std::vector<double> all;
        for (std::size_t i = 0; i < info.choices.size(); ++i) all.push_back(double(i));
        return all;
    }
    if (info.kind == ParamInfo::Kind::integer) return {info.min, 50.0, 5000.0, 123457.0};
    // Costs: C_I and C_child must be positive.
    return {0.0, 0.25, 3.0, 100.0, 1e6};
}

// The teapot's camera rays and random rays in all directions: nodes large and small, sampled
// and not, filtered and skipped, second children split (on two threads).
TEST(ParamNoEffect, AnInertParameterChangesNoHitAndNoCounter) {
    const Scene scene = load_obj(test::source_dir() / "assets/teapot/teapot.obj");
    std::vector<Ray> rays =
        PinholeProjection(scene.camera.value_or(frame_box(scene.bounds())), 96, 72)
            .pixel_centre_rays();
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
    const Aabb box = scene.bounds();
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 u(coord(rng), coord(rng), coord(rng));
        rays.push_back({0.5f * (box.lo + box.hi) + 0.5f * u * (box.hi - box.lo),
                        {coord(rng), coord(rng), coord(rng)}});
    }
    const std::vector<EdacrtParams> switches = {
        EdacrtParams{},
        paper_params(),
        dacrt_params(),
        with([](auto& p) { p.cost_leaf_max_tris = 16; }),
        with([](auto& p) { p.cost_leaf_max_tris = kAlwaysLeafTris; }),
        with([](auto& p) { p.leaf_tris = kAlwaysLeafTris; }),
        with([](auto& p) { p.filter_skip = FilterSkip::triangles; }),
        with([](auto& p) { p.cost_filter = 0.0f; }),
        with([](auto& p) { p.sample_threshold = 16; }),
        with([](auto& p) {
            p.small_nodes = SmallNodes::capped;
            p.sample_count = 10;
        }),
        with([](auto& p) {
            p.small_nodes = SmallNodes::scaled;
            p.sample_count = 1;
        }),
    };
    int checked = 0;
    for (const EdacrtParams& base : switches)
        for (int threads : {1, 2}) {
            const Outcome reference = trace(scene, rays, base, threads);
            ASSERT_GT(reference.levels.size(), 4u);
            if (threads > 1 && base.second_child == SecondChild::split) {
                double second_splits = 0.0;
                for (const auto& level : reference.levels) second_splits += level[6];
                EXPECT_GT(second_splits, 0.0) << "no second child was split";
            }
            for (const ParamInfo& info : edacrt_param_info()) {
                if (!param_no_effect_reason(base, info, threads)) continue;
                for (const double value : values(info)) {
                    EdacrtParams changed = base;
                    info.set(changed, value);
                    if (changed == base) continue;
                    try {
                        validate(changed);
                    } catch (const InputError&) {
                        continue;  // C_I or C_child of 0
                    }
                    SCOPED_TRACE(std::string(info.key) + " = " + param_text(changed, info) +
                                 " on " + std::to_string(threads) + " threads, from " +
                                 param_text(base, *find_param("filter-skip")) + " filter skip");
                    const Outcome outcome = trace(scene, rays, changed, threads);
                    ASSERT_EQ(std::memcmp(outcome.hits.data(), reference.hits.data(),
                                          rays.size() * sizeof(Hit)),
                              0);
                    EXPECT_EQ(outcome.totals.ray_box_tests, reference.totals.ray_box_tests);
                    EXPECT_EQ(outcome.totals.ray_triangle_tests,
                              reference.totals.ray_triangle_tests);
                    EXPECT_EQ(outcome.levels, reference.levels);
                    ++checked;
                }
            }
        }
    EXPECT_GT(checked, 100);
}

// And the converse for the defaults' live parameters, so the check above is not vacuous: a
// parameter reported to matter does change the trace for some value.
TEST(ParamNoEffect, ALiveParameterOfTheDefaultsChangesTheTrace) {
    const Scene scene = load_obj(test::source_dir() / "assets/teapot/teapot.obj");
    const std::vector<Ray> rays =
        PinholeProjection(scene.camera.value_or(frame_box(scene.bounds())), 128, 96)
            .pixel_centre_rays();
    const Outcome reference = trace(scene, rays, {}, 2);
    for (const char* key : {"sample-threshold", "sample-count", "small-nodes", "sampling-seed",
                            "c-i", "c-bv", "second-child", "hit-ratio", "order", "filter-skip"}) {
        const ParamInfo& info = *find_param(key);
        ASSERT_FALSE(param_no_effect_reason({}, info, 2)) << key;
        bool differs = false;
        for (const double value : values(info)) {
            EdacrtParams changed;
            info.set(changed, value);
            try {
                validate(changed);
            } catch (const InputError&) {
                continue;
            }
            const Outcome outcome = trace(scene, rays, changed, 2);
            differs |= outcome.totals.ray_box_tests != reference.totals.ray_box_tests ||
                       outcome.levels != reference.levels;
        }
        EXPECT_TRUE(differs) << key;
    }
}

}  // namespace
}  // namespace edacrt
