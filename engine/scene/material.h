#pragma once
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "scene/texture.h"

namespace edacrt {

/// A texture an MTL statement names (map_Kd, bump, ...). Only map_Kd is rendered (as
/// Material::diffuse_map); `edacrt info` lists them and the files that are missing.
struct TextureMap {
    std::string keyword;  // as written
    std::string file;     // as written
    std::string path;     // resolved beside the MTL file by load_obj; empty from parse_obj
};

/// The subset of a Wavefront MTL material the renderer models.
struct Material {
    std::string name = "default";
    glm::vec3 kd{0.8f};  // diffuse albedo
    glm::vec3 ks{0.0f};  // specular reflectance
    glm::vec3 ke{0.0f};  // emitted radiance
    glm::vec3 tf{1.0f};  // transmission filter (the tint of glass)
    float ns = 0.0f;     // specular exponent
    float ni = 1.0f;     // index of refraction
    int illum = 2;       // MTL illumination model
    std::vector<TextureMap> textures{};
    /// The decoded map_Kd (load_obj), which multiplies kd; null without one. Shared by the
    /// materials that name the same file and by copies of the scene.
    std::shared_ptr<const Texture> diffuse_map{};

    bool emissive() const { return ke.x > 0.0f || ke.y > 0.0f || ke.z > 0.0f; }
};

}  // namespace edacrt
