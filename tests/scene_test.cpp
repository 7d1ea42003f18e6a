// Built-in scenes and load_scene's dispatch.
#include <gtest/gtest.h>

#include <map>

#include "scene/builtin_scenes.h"
#include "test_paths.h"
#include "util/error.h"

namespace edacrt {
namespace {

/// Every edge of a closed, consistently wound mesh appears once in each direction.
void expect_closed_and_consistently_wound(const Scene& scene) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const auto& tri : scene.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{tri[k], tri[(k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
        ASSERT_EQ(count, 1) << "edge used twice in the same direction";
        ASSERT_EQ(directed.count({edge.second, edge.first}), 1u) << "open edge";
    }
}

void expect_well_formed(const Scene& scene) {
    ASSERT_FALSE(scene.materials.empty());
    ASSERT_EQ(scene.triangle_materials.size(), scene.triangles.size());
    for (const auto& tri : scene.triangles)
        for (std::uint32_t i : tri) ASSERT_LT(i, scene.positions.size());
    for (std::uint32_t m : scene.triangle_materials) ASSERT_LT(m, scene.materials.size());
}

TEST(BuiltinScenes, SphereIsClosedWithTheExpectedCount) {
    for (int n = 0; n <= 4; ++n) {
        const Scene scene = make_builtin_scene("builtin:sphere:subdiv=" + std::to_string(n));
        expect_well_formed(scene);
        EXPECT_EQ(scene.triangle_count(), 20u << (2 * n));
        expect_closed_and_consistently_wound(scene);
    }
}

TEST(BuiltinScenes, CubeIsClosedWithTheExpectedCount) {
    for (int n : {1, 3, 8}) {
        const Scene scene = make_builtin_scene("builtin:cube:n=" + std::to_string(n));
        expect_well_formed(scene);
        EXPECT_EQ(scene.triangle_count(), std::size_t(12 * n * n));
        expect_closed_and_consistently_wound(scene);
        EXPECT_EQ(scene.bounds().lo, glm::vec3(-1.0f));
        EXPECT_EQ(scene.bounds().hi, glm::vec3(1.0f));
    }
}

TEST(BuiltinScenes, SoupIsDeterministicPerSeed) {
    const Scene a = make_builtin_scene("builtin:soup:count=500,seed=9");
    const Scene b = make_builtin_scene("builtin:soup:count=500,seed=9");
    const Scene c = make_builtin_scene("builtin:soup:count=500,seed=10");
    expect_well_formed(a);
    EXPECT_EQ(a.triangle_count(), 500u);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_NE(a.positions, c.positions);
}

TEST(BuiltinScenes, CornellHasLightMaterialsAndCamera) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    expect_well_formed(scene);
    ASSERT_TRUE(scene.camera.has_value());
    int emissive = 0;
    for (std::uint32_t m : scene.triangle_materials) emissive += scene.materials[m].emissive();
    EXPECT_EQ(emissive, 2);  // one light quad
    EXPECT_EQ(scene.triangle_count(), 2u * (5 + 1 + 5 + 5));
}

TEST(BuiltinScenes, BadSpecsAreRejectedWithClearMessages) {
    const auto message = [](const std::string& spec) {
        try {
            make_builtin_scene(spec);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("builtin:teapot").find("unknown built-in scene"), std::string::npos);
    EXPECT_NE(message("builtin:teapot").find("builtin:sphere"), std::string::npos);
    EXPECT_NE(message("builtin:sphere:subdiv=12").find("subdiv"), std::string::npos);
    EXPECT_NE(message("builtin:sphere:subdiv=x").find("subdiv"), std::string::npos);
    EXPECT_NE(message("builtin:sphere:depth=2").find("unknown option 'depth'"), std::string::npos);
    EXPECT_NE(message("builtin:soup:count").find("key=value"), std::string::npos);
    EXPECT_NE(message("builtin:soup:count=-5").find("count"), std::string::npos);
}

TEST(LoadScene, DispatchesOnTheBuiltinPrefix) {
    EXPECT_EQ(load_scene("builtin:sphere:subdiv=1").triangle_count(), 80u);
    const Scene cornell =
        load_scene((test::source_dir() / "assets/cornell-box/CornellBox-Original.obj").string());
    EXPECT_EQ(cornell.triangle_count(), 36u);
    EXPECT_THROW(load_scene("/no/such/file.obj"), InputError);
}

}  // namespace
}  // namespace edacrt
