#pragma once
// What the integrators need beyond the geometry: a BSDF per material, the lights, and the
// surface at a hit (point with its error bound, normals, material).
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "geometry/offset.h"
#include "geometry/ray.h"
#include "render/bsdf.h"
#include "render/lights.h"
#include "scene/scene.h"

namespace edacrt {

struct Surface {
    SurfacePoint point;
    glm::vec3 ng_stored;  // unit geometric normal as the winding gives it
    glm::vec3 ng;         // ...turned towards the incoming ray
    glm::vec3 ns;         // unit shading normal on the side of ng
    std::uint32_t material;
    glm::vec3 texture{1.0f};  // the material's map_Kd at the hit, which multiplies Kd (1: none)
};

struct ShadingScene {
    explicit ShadingScene(const Scene& scene);

    std::vector<Bsdf> bsdfs;  // one per material
    Lights lights;
    Aabb bounds;
    float diagonal;                  // of `bounds`
    std::vector<std::string> notes;  // MTL settings that are approximated

    /// The BSDF at the surface: its material's, with Kd times the texture.
    Bsdf bsdf(const Surface& surface) const {
        Bsdf b = bsdfs[surface.material];
        b.kd *= surface.texture;
        return b;
    }
};

/// The surface `hit` (a hit of `ray`) lies on. Its texture needs texture coordinates at all
/// three corners; a triangle without them shows Kd alone.
Surface make_surface(const Scene& scene, const Ray& ray, const Hit& hit);

/// A ray from the surface towards the unit direction `dir`, up to `tmax` (no epsilon: the
/// origin is offset past the hit point's rounding error).
Ray spawn_ray(const Surface& surface, glm::vec3 dir, float tmax = kInfinity);

/// A ray from the surface to `target` that stops short of it (shadow rays towards lights).
Ray spawn_ray_to(const Surface& surface, glm::vec3 target);

}  // namespace edacrt
