// Dynamic scenes: every method, updated frame by frame with update_scene() as it would be in an
// animation (the BVH and Embree refitted or rebuilt, EDACRT and DACRT from the triangles),
// returns naive's hits on each deformed frame; updates report what they did.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <glm/geometric.hpp>
#include <tuple>

#include "agreement.h"
#include "scene/animation.h"
#include "test_paths.h"
#include "trace/bvh_tracer.h"
#include "trace/tracer.h"

namespace edacrt {
namespace {

struct Variant {
    std::string name;
    std::function<std::unique_ptr<Tracer>()> make;
    SceneUpdate how;
    UpdateWork work;    // what every update after the first does
    bool exact = true;  // our intersection kernel (see test::expect_agreement)
};

std::vector<Variant> variants() {
    const auto method = [](Method m, EmbreeMode mode = kDefaultEmbreeMode) {
        return [=] { return make_tracer(m, {}, mode); };
    };
    return {
        {"edacrt", method(Method::edacrt), SceneUpdate::rebuild, UpdateWork::none},
        {"dacrt", method(Method::dacrt), SceneUpdate::refit, UpdateWork::none},
        {"bvh rebuild", method(Method::bvh), SceneUpdate::rebuild, UpdateWork::rebuilt},
        {"bvh refit", method(Method::bvh), SceneUpdate::refit, UpdateWork::refitted},
#ifdef EDACRT_HAS_EMBREE
        {"embree rebuild", method(Method::embree), SceneUpdate::rebuild, UpdateWork::rebuilt,
         false},
        {"embree dynamic", method(Method::embree), SceneUpdate::dynamic, UpdateWork::rebuilt,
         false},
        {"embree refit", method(Method::embree), SceneUpdate::refit, UpdateWork::refitted, false},
        {"embree refit single", method(Method::embree, EmbreeMode::single), SceneUpdate::refit,
         UpdateWork::refitted, false},
#endif
    };
}

struct Case {
    const char* name;
    const char* scene;  // under the source directory, or builtin:; empty for animation files
    const char* animation;
};

const Case kCases[] = {
    {"spot_wave", "assets/spot/spot.obj", "wave:amplitude=0.05,wavelength=0.3"},
    {"teapot_twist", "assets/teapot/teapot.obj", "twist:angle=150"},
    {"cornell_explode", "builtin:cornell", "explode:distance=0.15"},
    {"rigid_objects", "", "assets/animations/spot-and-teapot.anim.json"},
};

std::string resolve(const char* path) {
    const std::string text = path;
    if (text.empty() || text.starts_with("builtin:") || text.find(':') != std::string::npos)
        return text;
    return (test::source_dir() / text).string();
}

/// A case, with the methods of our kernel (false) or Embree's modes (true).
class DynamicAgreement : public ::testing::TestWithParam<std::tuple<Case, bool>> {};

TEST_P(DynamicAgreement, EveryMethodMatchesNaiveOnEveryFrame) {
    const auto& [c, embree] = GetParam();
    AnimatedScene animated = load_animated_scene(resolve(c.scene), resolve(c.animation));
    Scene& scene = animated.scene;
    Animation& animation = *animated.animation;
    std::vector<Variant> chosen;
    for (const Variant& v : variants())
        if (v.exact != embree) chosen.push_back(v);
    if (chosen.empty()) GTEST_SKIP() << "this build has no Embree";
    std::vector<std::unique_ptr<Tracer>> tracers;
    for (const Variant& v : chosen) {
        tracers.push_back(v.make());
        // The first update builds whatever the method keeps (none for the recursions).
        const UpdateWork first = tracers.back()->update_scene(scene, v.how).work;
        EXPECT_EQ(first, v.work == UpdateWork::none ? UpdateWork::none : UpdateWork::rebuilt)
            << v.name;
    }
    // Frames far from the one the trees were built on: refitted boxes grow, hits must not
    // change. A quarter of the static test's rays keeps each case within seconds.
    for (const double share : {0.35, 0.8}) {
        const double t = share * animation.duration();
        animation.frame(t, scene);
        // Another kernel decides rays that start on a surface differently (TracerAgreement):
        // for Embree they start 1e-5 of the diagonal away.
        const float surface_tmin = embree ? 1e-5f * glm::length(scene.bounds().extent()) : 0.0f;
        const test::Reference reference = test::make_reference(scene, surface_tmin, 0.25f);
        for (std::size_t i = 0; i < chosen.size(); ++i) {
            const Variant& v = chosen[i];
            EXPECT_EQ(tracers[i]->update_scene(scene, v.how).work, v.work) << v.name;
            test::expect_agreement(
                scene, reference, *tracers[i],
                std::string(c.name) + " at t " + std::to_string(t) + " / " + v.name, v.exact);
            if (HasFatalFailure()) return;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Animations, DynamicAgreement,
                         ::testing::Combine(::testing::ValuesIn(kCases), ::testing::Bool()),
                         [](const auto& info) {
                             return std::string(std::get<0>(info.param).name) +
                                    (std::get<1>(info.param) ? "_embree" : "_ours");
                         });

TEST(BvhRefit, OnUnchangedGeometryGivesTheBuiltTreeBitForBit) {
    AnimatedScene animated =
        load_animated_scene((test::source_dir() / "assets/spot/spot.obj").string(), "twist");
    animated.animation->frame(0.7, animated.scene);
    BvhTracer built, refitted;
    built.set_scene(animated.scene);
    refitted.set_scene(animated.scene);
    animated.animation->frame(0.2, animated.scene);
    ASSERT_EQ(refitted.update_scene(animated.scene, SceneUpdate::refit).work, UpdateWork::refitted);
    animated.animation->frame(0.7, animated.scene);
    refitted.update_scene(animated.scene, SceneUpdate::refit);
    ASSERT_EQ(built.nodes().size(), refitted.nodes().size());
    for (std::size_t i = 0; i < built.nodes().size(); ++i)
        ASSERT_EQ(std::memcmp(&built.nodes()[i], &refitted.nodes()[i], sizeof(Bvh8Node)), 0)
            << "node " << i;
}

TEST(SceneUpdates, OtherTopologyIsRebuiltAndSaidSo) {
    const Scene a = load_scene("builtin:sphere:subdiv=2");
    const Scene b = load_scene("builtin:sphere:subdiv=3");
    Scene rewired = a;  // the same counts, other corners
    std::swap(rewired.triangles[0][0], rewired.triangles[0][1]);
    for (const Method m : {Method::bvh, Method::embree}) {
#ifndef EDACRT_HAS_EMBREE
        if (m == Method::embree) continue;
#endif
        for (const SceneUpdate how : {SceneUpdate::refit, SceneUpdate::dynamic}) {
            const std::string label = std::string(enum_name(kMethods, m)) + " " +
                                      std::string(enum_name(kSceneUpdates, how));
            const UpdateWork kept =
                how == SceneUpdate::refit ? UpdateWork::refitted : UpdateWork::rebuilt;
            const auto tracer = make_tracer(m);
            EXPECT_EQ(tracer->update_scene(a, how).work, UpdateWork::rebuilt) << label;
            if (m == Method::bvh && how == SceneUpdate::dynamic) continue;  // always rebuilds
            EXPECT_EQ(tracer->update_scene(a, how).work, kept) << label;
            const UpdateStats stats = tracer->update_scene(rewired, how);
            // The BVH refits any triangles of the same count; Embree's refit needs its indices.
            EXPECT_EQ(stats.work, m == Method::bvh ? kept : UpdateWork::rebuilt) << label;
            EXPECT_EQ(tracer->update_scene(b, how).work, UpdateWork::rebuilt) << label;
            EXPECT_EQ(tracer->update_scene(b, how).work, kept) << label;
            EXPECT_GE(stats.seconds, 0.0);
        }
    }
    EXPECT_EQ(make_tracer(Method::edacrt)->update_scene(a, SceneUpdate::refit).work,
              UpdateWork::none);
    EXPECT_EQ(make_tracer(Method::naive)->update_scene(a, SceneUpdate::rebuild).work,
              UpdateWork::none);
}

}  // namespace
}  // namespace edacrt
