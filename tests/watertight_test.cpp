// Watertightness (Woop et al. 2013) on closed tessellated meshes: rays through every vertex and
// every edge midpoint, from inside and from outside, must never fall between triangles.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <set>

#include "scene/builtin_scenes.h"
#include "trace/tracer.h"

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

/// From the centre (axis-aligned rays through the lattice) and, with inside_radius > 0, from
/// four random inside points, with every method: no ray falls through. Embree's robust mode is
/// not watertight through vertices (measured: 7 of 20,484 rays on a 5,120-triangle icosphere, with
/// Embree called directly too): it may lose at most 1 ray in 1000, and the count is printed.
void expect_no_misses(const std::string& spec, float inside_radius) {
    const Scene scene = make_builtin_scene(spec);
    const std::vector<glm::vec3> targets = vertex_and_edge_targets(scene);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coord(-inside_radius, inside_radius);
    std::vector<glm::vec3> insides = {glm::vec3(0.0f)};
    if (inside_radius > 0.0f)
        for (int i = 0; i < 4; ++i) insides.emplace_back(coord(rng), coord(rng), coord(rng));

    for (const auto& [method, name, help] : kMethods) {
        const auto tracer = make_tracer(method);
        tracer->set_scene(scene);
        for (const glm::vec3& inside : insides) {
            const std::vector<Ray> rays = rays_through(targets, inside);
            std::vector<Hit> hits(rays.size());
            for (const Query query : {Query::closest, Query::any}) {
                tracer->trace(rays, hits, query);
                const bool embree = name == "embree";
                std::size_t hit = 0;
                for (std::size_t i = 0; i < rays.size(); ++i) {
                    hit += hits[i].hit();
                    if (!hits[i].hit() && !embree)
                        ADD_FAILURE()
                            << spec << ", " << name << ": ray " << i << " from (" << rays[i].org.x
                            << ", " << rays[i].org.y << ", " << rays[i].org.z << ") fell through";
                }
                if (embree) {
                    if (hit < rays.size())
                        std::printf("%s, embree: %zu of %zu rays fell through\n", spec.c_str(),
                                    rays.size() - hit, rays.size());
                    ASSERT_GE(hit, rays.size() - rays.size() / 1000) << spec << ", embree";
                } else {
                    ASSERT_EQ(hit, rays.size()) << spec << ", " << name;
                }
            }
        }
    }
}

TEST(Watertight, IcosphereHasNoCracks) { expect_no_misses("builtin:sphere:subdiv=3", 0.5f); }

TEST(Watertight, TessellatedCubeHasNoCracks) { expect_no_misses("builtin:cube:n=8", 0.5f); }

TEST(Watertight, FineCubeFromItsCentreHitsEveryEdgeExactly) {
    // From the exact centre, rays towards lattice points are axis-parallel or pass exactly
    // through edges and vertices shared by up to six triangles.
    expect_no_misses("builtin:cube:n=20", 0.0f);
}

}  // namespace
}  // namespace edacrt
