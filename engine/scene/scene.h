#pragma once
#include <array>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/aabb.h"
#include "geometry/triangle.h"
#include "scene/camera.h"
#include "scene/material.h"

namespace edacrt {

/// An indexed triangle mesh with materials. Triangles are numbered in file order after
/// triangulation; that number is the `prim` of a Hit.
struct Scene {
    std::string source;  // file path or builtin:... name, for messages
    std::vector<glm::vec3> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions

    /// Optional shading normals: normals[triangle_normals[i][k]] for corner k of triangle i.
    /// triangle_normals is empty when no face had normals; a corner without one holds -1.
    std::vector<glm::vec3> normals;
    std::vector<std::array<std::int32_t, 3>> triangle_normals;
    /// Optional texture coordinates (u, v), indexed the same way (texcoords,
    /// triangle_texcoords).
    std::vector<glm::vec2> texcoords;
    std::vector<std::array<std::int32_t, 3>> triangle_texcoords;

    std::vector<std::uint32_t> triangle_materials;  // one per triangle, into materials
    std::vector<Material> materials;                // never empty once loaded

    std::optional<Camera> camera;       // a viewpoint the scene suggests, if any
    std::vector<std::string> warnings;  // problems that were repaired or skipped
    /// The files read to make it (OBJ, MTL libraries, animation file, key frames), so that a
    /// command can refuse an output that would overwrite one of them.
    std::vector<std::string> inputs;

    std::size_t triangle_count() const { return triangles.size(); }
    Triangle corners(std::size_t i) const {
        const auto& [a, b, c] = triangles[i];
        return {positions[a], positions[b], positions[c]};
    }
    Aabb bounds() const {
        Aabb box;
        for (const auto& tri : triangles)
            for (std::uint32_t i : tri) box.extend(positions[i]);
        return box;
    }
};

/// Loads "builtin:NAME[:key=value,...]" or an OBJ file path. Throws InputError.
Scene load_scene(const std::string& spec);

}  // namespace edacrt
