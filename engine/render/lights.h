#pragma once
// The emissive triangles of a scene as lights for next-event estimation: one is chosen in
// proportion to its power (area x luminance of Ke), then a point uniformly on it. Emitters
// shine on their front side only (the counter-clockwise winding's normal), as in pbrt and
// Mitsuba: a light 1 cm under a ceiling must not light the gap above it.
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "scene/scene.h"

namespace edacrt {

struct LightSample {
    glm::vec3 point;
    glm::vec3 normal;  // unit geometric normal of the emitter: its emitting side
    glm::vec3 radiance;
    std::uint32_t prim;
    float pdf_area;  // of choosing this point, per unit area
};

class Lights {
  public:
    explicit Lights(const Scene& scene);

    bool empty() const { return emitters_.empty(); }
    std::size_t size() const { return emitters_.size(); }

    /// A point on an emitter: `u_select` picks the triangle, `u` the point on it.
    LightSample sample(const Scene& scene, float u_select, glm::vec2 u) const;

    /// The pdf per unit area that sample() returns a point on triangle `prim`.
    float pdf_area(std::uint32_t prim) const;

  private:
    std::vector<std::uint32_t> emitters_;  // triangle numbers
    std::vector<float> cdf_;               // of the power, normalised, one per emitter
    std::vector<float> pdf_area_;          // per triangle of the scene (0 for non-emitters)
};

/// The unit geometric normal of triangle `prim`.
glm::vec3 unit_normal(const Scene& scene, std::uint32_t prim);

}  // namespace edacrt
