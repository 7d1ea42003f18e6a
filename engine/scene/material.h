#pragma once
#include <glm/vec3.hpp>
#include <string>

namespace edacrt {

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

    bool emissive() const { return ke.x > 0.0f || ke.y > 0.0f || ke.z > 0.0f; }
};

}  // namespace edacrt
