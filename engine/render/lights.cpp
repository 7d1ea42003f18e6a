#include "render/lights.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace edacrt {

glm::vec3 unit_normal(const Scene& scene, std::uint32_t prim) {
    return unit_normal(scene.corners(prim));
}

Lights::Lights(const Scene& scene) : pdf_area_(scene.triangle_count(), 0.0f) {
    std::vector<double> power;
    std::vector<double> areas;
    for (std::uint32_t prim = 0; prim < scene.triangle_count(); ++prim) {
        const Material& material = scene.materials[scene.triangle_materials[prim]];
        if (!material.emissive()) continue;
        const double area = triangle_area(scene.corners(prim));
        const glm::vec3 ke = material.ke;
        const double luminance = 0.2126 * ke.x + 0.7152 * ke.y + 0.0722 * ke.z;
        if (!(area > 0.0) || !(luminance > 0.0)) continue;
        emitters_.push_back(prim);
        power.push_back(area * luminance);
        areas.push_back(area);
    }
    double total = 0.0;
    for (double p : power) total += p;
    double running = 0.0;
    for (std::size_t i = 0; i < emitters_.size(); ++i) {
        running += power[i];
        cdf_.push_back(float(running / total));
        pdf_area_[emitters_[i]] = float(power[i] / total / areas[i]);
    }
    if (!cdf_.empty()) cdf_.back() = 1.0f;
}

LightSample Lights::sample(const Scene& scene, float u_select, glm::vec2 u) const {
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u_select);
    const std::size_t index = std::min(std::size_t(it - cdf_.begin()), emitters_.size() - 1);
    const std::uint32_t prim = emitters_[index];
    const Triangle tri = scene.corners(prim);
    // Uniform on the triangle (square-root parametrisation).
    const float s = std::sqrt(u.x);
    const float b1 = 1.0f - s, b2 = u.y * s;
    const glm::vec3 point = (1.0f - b1 - b2) * tri.p0 + b1 * tri.p1 + b2 * tri.p2;
    const Material& material = scene.materials[scene.triangle_materials[prim]];
    return {point, unit_normal(scene, prim), material.ke, prim, pdf_area_[prim]};
}

float Lights::pdf_area(std::uint32_t prim) const { return pdf_area_[prim]; }

}  // namespace edacrt
