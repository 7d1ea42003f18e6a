// Every tracer agrees with the naive reference on many random and adversarial ray sets:
// identical hit/miss, t within 1e-6 relative, the same triangle unless two are hit at the same t.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <optional>
#include <random>

#include "agreement.h"
#include "sanitizers.h"
#include "scene/builtin_scenes.h"
#include "scene/obj_loader.h"
#include "test_paths.h"
#include "trace/bvh_tracer.h"
#include "trace/edacrt_tracer.h"
#include "trace/naive_tracer.h"
#include "util/error.h"

namespace edacrt {
namespace {

using test::expect_agreement;
using test::make_ray_sets;
using test::make_reference;
using test::RaySets;
using test::Reference;

/// Overlapping, coplanar and duplicated triangles: ties and shared planes everywhere.
Scene coplanar_scene() {
    Scene scene = make_builtin_scene("builtin:soup:count=200,seed=5,size=0.4");
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
    for (int i = 0; i < 300; ++i) {
        const auto base = std::uint32_t(scene.positions.size());
        const float z = (i % 3 == 0) ? 0.0f : 0.5f;  // two shared planes
        for (int k = 0; k < 3; ++k) scene.positions.emplace_back(coord(rng), coord(rng), z);
        scene.triangles.push_back({base, base + 1, base + 2});
        if (i % 10 == 0) scene.triangles.push_back({base, base + 1, base + 2});  // duplicate
    }
    scene.triangle_materials.assign(scene.triangles.size(), 0);
    return scene;
}

const char* const kSceneNames[] = {
    "builtin:soup:count=2000,seed=1",
    "builtin:soup:count=3000,seed=2,size=0.3",
    "builtin:sphere:subdiv=3",
    "builtin:cornell",
    "builtin:cube:n=6",
    "coplanar",
    "spot.obj",
};

Scene test_scene(const std::string& name) {
    if (name == "coplanar") return coplanar_scene();
    if (name == "spot.obj") return load_obj(test::source_dir() / "assets/spot/spot.obj");
    return make_builtin_scene(name);
}

/// A tracer configuration under test.
struct Variant {
    std::string name;
    std::function<std::unique_ptr<Tracer>()> make;
    bool exact = true;  // shares our intersection kernel (see expect_agreement)
};

std::vector<Variant> variants() {
    std::vector<Variant> out = {
        {"bvh", [] { return make_tracer(Method::bvh); }},
        {"dacrt", [] { return make_tracer(Method::dacrt); }},
#ifdef EDACRT_HAS_EMBREE
        {"embree single", [] { return make_tracer(Method::embree, {}, EmbreeMode::single); },
         false},
        {"embree packet8", [] { return make_tracer(Method::embree, {}, EmbreeMode::packet8); },
         false},
        {"embree stream", [] { return make_tracer(Method::embree, {}, EmbreeMode::stream); },
         false},
#endif
    };
    const auto edacrt = [&](const std::string& name, auto edit) {
        EdacrtParams p;
        edit(p);
        out.push_back({name, [p] { return std::make_unique<EdacrtTracer>(p); }});
    };
    edacrt("edacrt", [](EdacrtParams&) {});
    edacrt("K=2", [](EdacrtParams& p) { p.bins = 2; });
    edacrt("K=64", [](EdacrtParams& p) { p.bins = 64; });
    edacrt("leaf=1", [](EdacrtParams& p) { p.leaf_rays = p.leaf_tris = 1; });
    edacrt("leaf=1e6 (naive)", [](EdacrtParams& p) { p.leaf_rays = p.leaf_tris = 1'000'000; });
    edacrt("1 sample", [](EdacrtParams& p) {
        p.sample_count = 1;
        p.sample_threshold = 1;
    });
    edacrt("filter skip off", [](EdacrtParams& p) { p.filter_skip = FilterSkip::off; });
    edacrt("paper preset", [](EdacrtParams& p) { p = paper_params(); });
    edacrt("far child unstopped", [](EdacrtParams& p) { p.far_child = FarChild::unstopped; });
    edacrt("dacrt, sampled alpha, far child unstopped", [](EdacrtParams& p) {
        p = dacrt_params();
        p.hit_ratio = HitRatio::sampled;
        p.far_child = FarChild::unstopped;
    });
    edacrt("leaf by cost anywhere", [](EdacrtParams& p) { p.cost_leaf_max_tris = 1'000'000; });
    edacrt("always skip filtering", [](EdacrtParams& p) { p.cost_filter = 1e9f; });
    return out;
}

class TracerAgreement : public ::testing::TestWithParam<const char*> {};

TEST_P(TracerAgreement, EveryVariantMatchesNaive) {
    const Scene scene = test_scene(GetParam());
    const Reference reference = make_reference(scene);
    // A kernel other than ours decides differently whether a ray hits the surface it starts on
    // (t within rounding of 0): for those tracers, rays from surfaces begin 1e-5 of the scene's
    // diagonal away (renderers offset such rays anyway), and the reference is traced the same.
    std::optional<Reference> offset_reference;
    for (const Variant& variant : variants()) {
        if (!variant.exact && !offset_reference)
            offset_reference = make_reference(scene, 1e-5f * glm::length(scene.bounds().extent()));
        const auto tracer = variant.make();
        tracer->set_scene(scene);
        expect_agreement(scene, variant.exact ? reference : *offset_reference, *tracer,
                         std::string(GetParam()) + " / " + variant.name, variant.exact);
        if (HasFatalFailure()) return;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, TracerAgreement, ::testing::ValuesIn(kSceneNames),
                         [](const auto& info) {
                             std::string name;
                             for (const char c : std::string(info.param))
                                 name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return name;
                         });

/// Every combination of EDACRT's switches (hit ratio, order, filter skipping, small-node
/// policy, binning): 180 recursions, each exact, half of them with the second child split and
/// half after the first, and a third each with 0, 0.5 and 1 extra triangle pieces per triangle,
/// alternating. Small leaves make the recursion deep. Under the sanitizers, whose point here is
/// every combination's code path, each ray set is a quarter as large.
class AblationSwitches : public ::testing::TestWithParam<const char*> {};

TEST_P(AblationSwitches, EveryCombinationMatchesNaive) {
    const Scene scene = test_scene(GetParam());
    const Reference reference = make_reference(scene, 0.0f, test::kSanitized ? 0.25f : 1.0f);
    int combinations = 0;
    for (int hit_ratio = 0; hit_ratio < 2; ++hit_ratio)
        for (int order = 0; order < 3; ++order)
            for (int skip = 0; skip < 3; ++skip)
                for (int small = 0; small < int(kSmallNodes.size()); ++small)
                    for (int binning = 0; binning < 2; ++binning) {
                        EdacrtParams p;
                        p.hit_ratio = HitRatio(hit_ratio);
                        p.order = TraversalOrder(order);
                        p.filter_skip = FilterSkip(skip);
                        p.small_nodes = SmallNodes(small);
                        p.binning = Binning(binning);
                        p.second_child = SecondChild(combinations % 2);
                        p.presplit = 0.5f * float(combinations % 3);  // 0, 0.5, 1
                        p.leaf_rays = p.leaf_tris = 4;
                        p.sample_threshold = 200;
                        p.sample_count = 20;
                        EdacrtTracer tracer(p);
                        tracer.set_scene(scene);
                        std::string label = std::string(GetParam()) + " / switches";
                        for (const ParamInfo* info :
                             {find_param("hit-ratio"), find_param("order"),
                              find_param("filter-skip"), find_param("small-nodes"),
                              find_param("binning"), find_param("second-child"),
                              find_param("presplit")})
                            label += " " + param_text(p, *info);
                        expect_agreement(scene, reference, tracer, label, true);
                        if (HasFatalFailure()) return;
                        ++combinations;
                    }
    EXPECT_EQ(combinations, 2 * 3 * 3 * int(kSmallNodes.size()) * 2);
}

INSTANTIATE_TEST_SUITE_P(Scenes, AblationSwitches,
                         ::testing::Values("builtin:soup:count=2000,seed=1", "coplanar",
                                           "builtin:cornell"),
                         [](const auto& info) {
                             std::string name;
                             for (const char c : std::string(info.param))
                                 name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return name;
                         });

/// A batch large enough for the parallel paths (partitions of >= 8192 rays, leaves of >= 32768
/// ray-triangle pairs), ray by ray against naive. (Parallel binning, from 8192 triangles, is
/// checked against serial binning by the thread tests.)
TEST(EdacrtLargeBatch, MatchesNaiveRayByRay) {
    const Scene scene = make_builtin_scene("builtin:soup:count=2000,seed=6,size=0.3");
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Ray> rays;
    const PinholeProjection projection(frame_box(scene.bounds()), 320, 320);
    for (int y = 0; y < 320; ++y)
        for (int x = 0; x < 320; ++x) rays.push_back(projection.ray(x + unit(rng), y + unit(rng)));
    for (int i = 0; i < 20'000; ++i) {
        const glm::vec3 o(unit(rng) * 2 - 1, unit(rng) * 2 - 1, unit(rng) * 2 - 1);
        rays.push_back({o, glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f)});
    }
    ASSERT_GE(rays.size(), 100'000u);
    // The naive reference (2000 triangles per ray) takes most of the time under the sanitizers:
    // there it answers every 8th ray, while EDACRT still traces the whole batch.
    const std::size_t stride = test::kSanitized ? 8 : 1;
    std::vector<Ray> checked;
    for (std::size_t i = 0; i < rays.size(); i += stride) checked.push_back(rays[i]);
    NaiveTracer naive;
    naive.set_scene(scene);
    for (const Query query : {Query::closest, Query::any}) {
        std::vector<Hit> expected(checked.size()), got(rays.size());
        naive.trace(checked, expected, query);
        for (const EdacrtParams& p : {EdacrtParams{}, paper_params(), dacrt_params()}) {
            EdacrtTracer tracer(p);
            tracer.set_scene(scene);
            tracer.trace(rays, got, query);
            std::size_t differences = 0, hits = 0;
            for (std::size_t j = 0; j < checked.size(); ++j) {
                const Hit& want = expected[j];
                const Hit& hit = got[j * stride];
                hits += want.hit();
                // A soup has no shared edges: closest hits are unique.
                const bool same = query == Query::any ? hit.hit() == want.hit()
                                                      : hit.prim == want.prim && hit.t == want.t;
                if (!same && ++differences <= 5)
                    ADD_FAILURE() << "ray " << j * stride << ": prim " << hit.prim << " t " << hit.t
                                  << ", naive prim " << want.prim << " t " << want.t;
            }
            EXPECT_EQ(differences, 0u);
            EXPECT_GT(hits, checked.size() / 4);
        }
    }
}

TEST(EdacrtStats, TestsFewerTrianglesThanNaive) {
    const Scene scene = make_builtin_scene("builtin:sphere:subdiv=5");
    const RaySets sets = make_ray_sets(scene, 1);
    const std::vector<Ray>& rays = sets.sets[0].second;
    std::vector<Hit> hits(rays.size());
    EdacrtTracer tracer;
    tracer.set_scene(scene);
    const TraceStats stats = tracer.trace(rays, hits, Query::closest);
    EXPECT_EQ(stats.rays, rays.size());
    // Measured: 37 box and 78 triangle tests per camera ray on these 20,480 triangles (naive
    // makes 20,480 triangle tests per ray); twice that is a regression.
    EXPECT_GE(stats.ray_box_tests, rays.size());  // at least the root filter
    EXPECT_LT(stats.ray_box_tests, 75 * rays.size());
    EXPECT_LT(stats.ray_triangle_tests, 160 * rays.size());
}

TEST(Bvh, EveryTriangleIsInALeafAndChildrenNestInParents) {
    const Scene scene = make_builtin_scene("builtin:soup:count=3000,seed=3");
    BvhTracer bvh;
    bvh.set_scene(scene);
    const auto& nodes = bvh.nodes();
    std::size_t in_leaves = 0, leaves = 0, inner = 0;
    std::vector<bool> seen(scene.triangle_count(), false);
    for (const Bvh8Node& node : nodes) {
        for (int lane = 0; lane < 8; ++lane) {
            const Aabb box{
                {node.boxes.lo[0][lane], node.boxes.lo[1][lane], node.boxes.lo[2][lane]},
                {node.boxes.hi[0][lane], node.boxes.hi[1][lane], node.boxes.hi[2][lane]}};
            if (box.empty()) continue;  // an unused lane
            if (node.count[lane] > 0) {
                in_leaves += node.count[lane];
                ++leaves;
                for (std::uint32_t k = node.child[lane]; k < node.child[lane] + node.count[lane];
                     ++k)
                    seen[bvh.prims()[k]] = true;
                continue;
            }
            ++inner;
            ASSERT_LT(node.child[lane], nodes.size());
            const Boxes8& children = nodes[node.child[lane]].boxes;
            for (int c = 0; c < 8; ++c) {
                if (children.lo[0][c] > children.hi[0][c]) continue;
                for (int axis = 0; axis < 3; ++axis) {
                    EXPECT_LE(box.lo[axis], children.lo[axis][c]);
                    EXPECT_GE(box.hi[axis], children.hi[axis][c]);
                }
            }
        }
    }
    EXPECT_EQ(in_leaves, bvh.prims().size());
    EXPECT_EQ(in_leaves, scene.triangle_count());
    EXPECT_EQ(std::count(seen.begin(), seen.end(), false), 0);
    EXPECT_EQ(inner + 1, nodes.size());             // every node but the root is one inner lane
    EXPECT_GT(leaves, scene.triangle_count() / 8);  // a real hierarchy, not one big leaf
}

TEST(EdacrtParams, OutOfRangeParametersAreRejected) {
    const auto rejects = [](auto edit) {
        EdacrtParams p;
        edit(p);
        EXPECT_THROW(validate(p), InputError);
    };
    rejects([](EdacrtParams& p) { p.bins = 1; });
    rejects([](EdacrtParams& p) { p.bins = 1000; });
    rejects([](EdacrtParams& p) { p.leaf_rays = 0; });
    rejects([](EdacrtParams& p) { p.leaf_tris = 0; });
    rejects([](EdacrtParams& p) { p.sample_count = 0; });
    rejects([](EdacrtParams& p) { p.cost_intersect = -1.0f; });
    rejects([](EdacrtParams& p) { p.cost_traversal = NAN; });
    EXPECT_NO_THROW(validate(EdacrtParams{}));
    EXPECT_NO_THROW(validate(dacrt_params()));
    EXPECT_THROW(make_tracer(Method::edacrt, EdacrtParams{.bins = 0}), InputError);
}

}  // namespace
}  // namespace edacrt
