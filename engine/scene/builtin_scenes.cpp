#include "scene/builtin_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "util/error.h"
#include "util/spec_options.h"

namespace edacrt {
namespace {

void finish(Scene& scene, std::string_view spec) {
    scene.source = std::string(spec);
    if (scene.materials.empty()) scene.materials.push_back(Material{});
    scene.triangle_materials.resize(scene.triangles.size(), 0);
}

/// Icosphere: an icosahedron whose edges are split N times, the new vertices pushed onto the
/// unit sphere. Midpoints are shared through an edge map, so the mesh stays closed.
Scene make_sphere(int subdivisions) {
    Scene scene;
    const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
    for (const glm::vec3 p :
         {glm::vec3(-1, g, 0), glm::vec3(1, g, 0), glm::vec3(-1, -g, 0), glm::vec3(1, -g, 0),
          glm::vec3(0, -1, g), glm::vec3(0, 1, g), glm::vec3(0, -1, -g), glm::vec3(0, 1, -g),
          glm::vec3(g, 0, -1), glm::vec3(g, 0, 1), glm::vec3(-g, 0, -1), glm::vec3(-g, 0, 1)})
        scene.positions.push_back(glm::normalize(p));
    scene.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [it, inserted] =
                midpoints.try_emplace(key, static_cast<std::uint32_t>(scene.positions.size()));
            if (inserted)
                scene.positions.push_back(glm::normalize(scene.positions[a] + scene.positions[b]));
            return it->second;
        };
        std::vector<std::array<std::uint32_t, 3>> finer;
        finer.reserve(scene.triangles.size() * 4);
        for (const auto [a, b, c] : scene.triangles) {
            const std::uint32_t ab = midpoint(a, b);
            const std::uint32_t bc = midpoint(b, c);
            const std::uint32_t ca = midpoint(c, a);
            finer.push_back({a, ab, ca});
            finer.push_back({b, bc, ab});
            finer.push_back({c, ca, bc});
            finer.push_back({ab, bc, ca});
        }
        scene.triangles = std::move(finer);
    }
    return scene;
}

/// The cube [-1,1]^3 with an n x n grid of quads per face; vertices live on an integer
/// lattice so that faces meeting at an edge share them exactly.
Scene make_cube(int n) {
    Scene scene;
    std::map<std::tuple<int, int, int>, std::uint32_t> lattice;
    const auto vertex = [&](int i, int j, int k) {
        const auto [it, inserted] =
            lattice.try_emplace({i, j, k}, static_cast<std::uint32_t>(scene.positions.size()));
        if (inserted)
            scene.positions.push_back(glm::vec3(i, j, k) * (2.0f / float(n)) - glm::vec3(1.0f));
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
            for (int a = 0; a < n; ++a) {
                for (int b = 0; b < n; ++b) {
                    const auto corner = [&](int da, int db) {
                        int c[3];
                        c[axis] = side * n;
                        c[u_axis] = a + da;
                        c[v_axis] = b + db;
                        return vertex(c[0], c[1], c[2]);
                    };
                    const std::uint32_t q0 = corner(0, 0), q1 = corner(1, 0), q2 = corner(1, 1),
                                        q3 = corner(0, 1);
                    // Wind counter-clockwise seen from outside.
                    if (side == 1) {
                        scene.triangles.push_back({q0, q1, q2});
                        scene.triangles.push_back({q0, q2, q3});
                    } else {
                        scene.triangles.push_back({q0, q2, q1});
                        scene.triangles.push_back({q0, q3, q2});
                    }
                }
            }
        }
    }
    return scene;
}

/// Random triangles: a uniform centre in [-1,1]^3 and corners within `size` of it. A portable
/// generator (mt19937 and explicit scaling) so a seed means the same soup everywhere.
Scene make_soup(int count, std::uint32_t seed, float size) {
    Scene scene;
    std::mt19937 rng(seed);
    const auto uniform = [&] { return float(rng() >> 8) * (2.0f / 16777216.0f) - 1.0f; };
    while (scene.triangles.size() < std::size_t(count)) {
        const glm::vec3 centre(uniform(), uniform(), uniform());
        const std::uint32_t base = static_cast<std::uint32_t>(scene.positions.size());
        glm::vec3 p[3];
        for (glm::vec3& corner : p)
            corner = centre + size * glm::vec3(uniform(), uniform(), uniform());
        if (glm::length(glm::cross(p[1] - p[0], p[2] - p[0])) == 0.0f) continue;
        for (const glm::vec3& corner : p) scene.positions.push_back(corner);
        scene.triangles.push_back({base, base + 1, base + 2});
    }
    return scene;
}

/// The Cornell box after the Cornell measurements, scaled to [-1,1] x [0,2] x [-1,1] and
/// open towards +z, with an emissive quad under the ceiling.
Scene make_cornell() {
    Scene scene;
    scene.materials = {
        {"white", glm::vec3(0.725f, 0.71f, 0.68f)},
        {"red", glm::vec3(0.63f, 0.065f, 0.05f)},
        {"green", glm::vec3(0.14f, 0.45f, 0.091f)},
        {"light", glm::vec3(0.78f), glm::vec3(0.0f), glm::vec3(17.0f, 12.0f, 4.0f)},
    };
    const auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, std::uint32_t m) {
        const std::uint32_t base = static_cast<std::uint32_t>(scene.positions.size());
        for (const glm::vec3& p : {a, b, c, d}) scene.positions.push_back(p);
        scene.triangles.push_back({base, base + 1, base + 2});
        scene.triangles.push_back({base, base + 2, base + 3});
        scene.triangle_materials.insert(scene.triangle_materials.end(), 2, m);
    };
    using glm::vec3;
    quad(vec3(-1, 0, 1), vec3(1, 0, 1), vec3(1, 0, -1), vec3(-1, 0, -1), 0);    // floor
    quad(vec3(-1, 2, 1), vec3(-1, 2, -1), vec3(1, 2, -1), vec3(1, 2, 1), 0);    // ceiling
    quad(vec3(-1, 0, -1), vec3(1, 0, -1), vec3(1, 2, -1), vec3(-1, 2, -1), 0);  // back
    quad(vec3(-1, 0, 1), vec3(-1, 0, -1), vec3(-1, 2, -1), vec3(-1, 2, 1), 1);  // left, red
    quad(vec3(1, 0, -1), vec3(1, 0, 1), vec3(1, 2, 1), vec3(1, 2, -1), 2);      // right, green
    quad(vec3(-0.24f, 1.98f, -0.22f), vec3(0.23f, 1.98f, -0.22f), vec3(0.23f, 1.98f, 0.16f),
         vec3(-0.24f, 1.98f, 0.16f), 3);  // light, facing down
    // A block: four sides and a top, rotated by `angle` about its centre (cx, cz).
    const auto block = [&](float cx, float cz, float half, float height, float angle) {
        const float c = std::cos(angle), s = std::sin(angle);
        const auto corner = [&](float x, float z, float y) {
            return vec3(cx + c * x - s * z, y, cz + s * x + c * z);
        };
        vec3 bottom[4], top[4];
        const float xs[4] = {-half, half, half, -half}, zs[4] = {half, half, -half, -half};
        for (int i = 0; i < 4; ++i) {
            bottom[i] = corner(xs[i], zs[i], 0.0f);
            top[i] = corner(xs[i], zs[i], height);
        }
        for (int i = 0; i < 4; ++i) {
            const int j = (i + 1) % 4;
            quad(bottom[i], bottom[j], top[j], top[i], 0);
        }
        quad(top[0], top[1], top[2], top[3], 0);
    };
    block(0.33f, 0.3f, 0.3f, 0.6f, -0.29f);   // short block, front right
    block(-0.34f, -0.3f, 0.3f, 1.2f, 0.29f);  // tall block, back left
    scene.camera = Camera{vec3(0.0f, 1.0f, 3.9f), vec3(0.0f, 1.0f, 0.0f), vec3(0, 1, 0), 38.0f};
    return scene;
}

}  // namespace

Scene make_builtin_scene(std::string_view spec) {
    const std::string_view body = spec.substr(std::string_view("builtin:").size());
    const std::size_t colon = body.find(':');
    const std::string_view name = body.substr(0, colon);
    SpecOptions options(spec, colon == std::string_view::npos ? "" : body.substr(colon + 1));
    Scene scene;
    if (name == "cornell") {
        scene = make_cornell();
    } else if (name == "sphere") {
        scene = make_sphere(options.number("subdiv", 3, 0, 9));
    } else if (name == "cube") {
        scene = make_cube(options.number("n", 4, 1, 1000));
    } else if (name == "soup") {
        const int count = options.number("count", 1000, 1, 10'000'000);
        const auto seed = options.number<std::uint32_t>("seed", 1, 0, UINT32_MAX);
        const float size = options.number("size", 0.1f, 1e-6f, 10.0f);
        scene = make_soup(count, seed, size);
    } else {
        throw InputError("unknown built-in scene '" + std::string(spec) + "'; available:\n" +
                         builtin_scene_help());
    }
    options.finish();
    finish(scene, spec);
    return scene;
}

std::string builtin_scene_help() {
    return "  builtin:cornell                        Cornell box with area light\n"
           "  builtin:sphere[:subdiv=N]              closed icosphere, 20*4^N triangles\n"
           "  builtin:cube[:n=N]                     closed cube, N x N quads per face\n"
           "  builtin:soup[:count=N,seed=S,size=F]   N random triangles in [-1,1]^3\n";
}

}  // namespace edacrt
