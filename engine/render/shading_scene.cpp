#include "render/shading_scene.h"

#include <array>
#include <cstdint>
#include <glm/geometric.hpp>
#include <optional>
#include <vector>

namespace edacrt {

ShadingScene::ShadingScene(const Scene& scene) : lights(scene) {
    for (const Material& material : scene.materials) bsdfs.push_back(make_bsdf(material, &notes));
    bounds = scene.bounds();
    diagonal = bounds.empty() ? 0.0f : glm::length(bounds.hi - bounds.lo);
}

namespace {

/// The per-corner `values` of triangle `prim` (indices `corners`, empty: none) interpolated at
/// the hit; empty unless all three corners have one.
template <class T>
std::optional<T> at_hit(const std::vector<T>& values,
                        const std::vector<std::array<std::int32_t, 3>>& corners, std::size_t prim,
                        const Hit& hit) {
    if (corners.empty()) return std::nullopt;
    const auto& [a, b, c] = corners[prim];
    if (a < 0 || b < 0 || c < 0) return std::nullopt;
    return (1.0f - hit.u - hit.v) * values[std::size_t(a)] + hit.u * values[std::size_t(b)] +
           hit.v * values[std::size_t(c)];
}

}  // namespace

Surface make_surface(const Scene& scene, const Ray& ray, const Hit& hit) {
    const auto prim = std::size_t(hit.prim);
    const Triangle tri = scene.corners(prim);
    Surface s;
    s.point = surface_point(tri, hit.u, hit.v);
    s.ng_stored = unit_normal(tri);
    s.ng = glm::dot(s.ng_stored, ray.dir) < 0.0f ? s.ng_stored : -s.ng_stored;
    s.ns = s.ng;
    if (const auto n = at_hit(scene.normals, scene.triangle_normals, prim, hit)) {
        const float length = glm::length(*n);
        if (length > 0.0f) s.ns = glm::dot(*n, s.ng) < 0.0f ? -*n / length : *n / length;
    }
    s.material = scene.triangle_materials[prim];
    const Material& material = scene.materials[s.material];
    if (material.diffuse_map)
        if (const auto uv = at_hit(scene.texcoords, scene.triangle_texcoords, prim, hit))
            s.texture = material.diffuse_map->lookup(*uv);
    return s;
}

Ray spawn_ray(const Surface& surface, glm::vec3 dir, float tmax) {
    return Ray{offset_ray_origin(surface.point, surface.ng, dir), dir, kSpawnTmin, tmax};
}

Ray spawn_ray_to(const Surface& surface, glm::vec3 target) {
    const glm::vec3 origin = offset_ray_origin(surface.point, surface.ng, target - surface.point.p);
    const glm::vec3 d = target - origin;
    const float distance = glm::length(d);
    // Stop a relative 1e-4 short so the emitter's own triangle does not occlude (pbrt's
    // ShadowEpsilon): relative, so it holds at any scene scale.
    return Ray{origin, d / distance, kSpawnTmin, distance * (1.0f - 1e-4f)};
}

}  // namespace edacrt
