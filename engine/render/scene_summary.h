#pragma once
// What a scene is, before rendering it (`edacrt info`): its size, what each material models,
// its emitters and bounds, and what the renderer will not show (textures, unmodelled MTL
// statements, degenerate triangles).
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/aabb.h"
#include "scene/scene.h"

namespace edacrt {

struct MaterialSummary {
    std::string name;
    std::size_t triangles = 0;  // that use it
    std::string model;          // what the renderer makes of it ("Lambertian Kd 0.8 0.8 0.8")
    bool emissive = false;
    std::vector<TextureMap> textures;                // named by the MTL
    std::size_t rendered_texture = std::size_t(-1);  // the one rendered (map_Kd), if any
};

struct SceneSummary {
    std::size_t triangles = 0;
    std::size_t degenerate_triangles = 0;  // zero area: kept for numbering, never hit
    std::size_t vertices = 0;
    std::size_t shading_normals = 0;
    std::vector<MaterialSummary> materials;
    std::size_t emissive_triangles = 0;  // with positive area, as the lights sample them
    double emissive_area = 0.0;
    Aabb bounds;
    /// The loader's warnings, then missing texture files and the materials' approximations.
    std::vector<std::string> warnings;
};

SceneSummary summarize_scene(const Scene& scene);

}  // namespace edacrt
