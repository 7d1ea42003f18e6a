#include "render/shading_scene.h"

#include <glm/geometric.hpp>

namespace edacrt {

ShadingScene::ShadingScene(const Scene& scene) : lights(scene) {
    for (const Material& material : scene.materials) bsdfs.push_back(make_bsdf(material, &notes));
    bounds = scene.bounds();
    diagonal = bounds.empty() ? 0.0f : glm::length(bounds.hi - bounds.lo);
}

Surface make_surface(const Scene& scene, const Ray& ray, const Hit& hit) {
    const auto prim = std::size_t(hit.prim);
    const Triangle tri = scene.corners(prim);
    Surface s;
    s.point = surface_point(tri, hit.u, hit.v);
    s.ng_stored = unit_normal(tri);
    s.ng = glm::dot(s.ng_stored, ray.dir) < 0.0f ? s.ng_stored : -s.ng_stored;
    s.ns = s.ng;
    if (!scene.triangle_normals.empty()) {
        const auto& corners = scene.triangle_normals[prim];
        if (corners[0] >= 0 && corners[1] >= 0 && corners[2] >= 0) {
            const glm::vec3 n = (1.0f - hit.u - hit.v) * scene.normals[std::size_t(corners[0])] +
                                hit.u * scene.normals[std::size_t(corners[1])] +
                                hit.v * scene.normals[std::size_t(corners[2])];
            const float length = glm::length(n);
            if (length > 0.0f) s.ns = glm::dot(n, s.ng) < 0.0f ? -n / length : n / length;
        }
    }
    s.material = scene.triangle_materials[prim];
    const Material& material = scene.materials[s.material];
    if (material.diffuse_map && !scene.triangle_texcoords.empty()) {
        const auto& corners = scene.triangle_texcoords[prim];
        if (corners[0] >= 0 && corners[1] >= 0 && corners[2] >= 0) {
            const glm::vec2 uv = (1.0f - hit.u - hit.v) * scene.texcoords[std::size_t(corners[0])] +
                                 hit.u * scene.texcoords[std::size_t(corners[1])] +
                                 hit.v * scene.texcoords[std::size_t(corners[2])];
            s.texture = material.diffuse_map->lookup(uv);
        }
    }
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
