// Watertightness (Woop et al. 2013) on closed tessellated meshes: rays through every vertex and
// every edge midpoint, from inside and from outside, must never fall between triangles.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "scene/builtin_scenes.h"
#include "trace/naive_tracer.h"

namespace edacrt {
namespace {

/// Every vertex and every edge midpoint of the mesh.
std::vector<glm::vec3> vertex_and_edge_targets(const Scene& scene) {
    std::vector<glm::vec3> targets(scene.positions.begin(), scene.positions.end());
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& tri : scene.triangles)
        for (int k = 0; k < 3; ++k) edges.insert(std::minmax(tri[k], tri[(k + 1) % 3]));
    for (const auto& [a, b] : edges)
        targets.push_back(0.5f * (scene.positions[a] + scene.positions[b]));
    return targets;
}

/// Rays that must hit a closed mesh containing `inside`: from the inside point through each
/// target, and from outside through each target towards the inside point.
std::vector<Ray> rays_through(const std::vector<glm::vec3>& targets, const glm::vec3& inside) {
    std::vector<Ray> rays;
    for (const glm::vec3& target : targets) {
        rays.push_back({inside, target - inside});
        const glm::vec3 outside = inside + 3.0f * (target - inside);
        rays.push_back({outside, inside - outside});
    }
    return rays;
}

void expect_no_misses(const std::string& spec, float inside_radius) {
    const Scene scene = make_builtin_scene(spec);
    NaiveTracer tracer;
    tracer.set_scene(scene);
    const std::vector<glm::vec3> targets = vertex_and_edge_targets(scene);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coord(-inside_radius, inside_radius);
    std::vector<glm::vec3> insides = {glm::vec3(0.0f)};  // the centre makes axis-aligned rays
    for (int i = 0; i < 4; ++i) insides.emplace_back(coord(rng), coord(rng), coord(rng));

    std::size_t traced = 0;
    for (const glm::vec3& inside : insides) {
        const std::vector<Ray> rays = rays_through(targets, inside);
        std::vector<Hit> hits(rays.size());
        for (const Query query : {Query::closest, Query::any}) {
            tracer.trace(rays, hits, query);
            for (std::size_t i = 0; i < rays.size(); ++i)
                ASSERT_TRUE(hits[i].hit())
                    << spec << ": ray " << i << " from (" << rays[i].org.x << ", " << rays[i].org.y
                    << ", " << rays[i].org.z << ") fell through";
            traced += rays.size();
        }
    }
    EXPECT_GT(traced, 4 * targets.size());
}

TEST(Watertight, IcosphereHasNoCracks) { expect_no_misses("builtin:sphere:subdiv=4", 0.5f); }

TEST(Watertight, TessellatedCubeHasNoCracks) { expect_no_misses("builtin:cube:n=8", 0.5f); }

TEST(Watertight, FineCubeFromItsCentreHitsEveryEdgeExactly) {
    // From the exact centre, rays towards lattice points are axis-parallel or pass exactly
    // through edges and vertices shared by up to six triangles.
    expect_no_misses("builtin:cube:n=20", 0.0f);
}

}  // namespace
}  // namespace edacrt
