#pragma once
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

#include "geometry/aabb.h"
#include "geometry/ray.h"

namespace edacrt {

/// A pinhole camera.
struct Camera {
    glm::vec3 eye{0.0f, 0.0f, 1.0f};
    glm::vec3 look_at{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float vfov_degrees = 45.0f;

    bool operator==(const Camera&) const = default;
};

/// The side frame_box() looks from: +z (the open side of a Cornell box), or +x when the box is
/// clearly deeper (z) than wide (x), for a side view of what is long along z (an animal, a
/// vehicle: Spot the cow showed its back) rather than its end. "+z" or "+x".
const char* framing_side(const Aabb& box, float vfov_degrees = 45.0f);

/// A camera that looks at the box from framing_side() and sees all of it.
Camera frame_box(const Aabb& box, float vfov_degrees = 45.0f);

/// Throws InputError when the camera cannot form an image (eye == look_at, up parallel to the
/// view direction, fov outside (0, 180), non-finite values).
void validate(const Camera& camera);

/// Camera rays for an image of width x height: precomputes the image plane once.
class PinholeProjection {
  public:
    PinholeProjection(const Camera& camera, int width, int height);

    /// The ray through image position (x, y) in pixels; (0, 0) is the top-left corner of the
    /// top-left pixel, (width, height) the bottom-right corner of the image.
    Ray ray(float x, float y) const;

    glm::vec3 eye() const { return eye_; }

    /// Where `point` appears in the image, in pixels (the inverse of ray()); empty when it is
    /// not in front of the camera.
    std::optional<glm::vec2> pixel(const glm::vec3& point) const;

    /// One ray through each pixel centre, row by row from the top-left.
    std::vector<Ray> pixel_centre_rays() const;

  private:
    glm::vec3 eye_;
    glm::vec3 forward_, right_, up_;
    float half_width_, half_height_;
    glm::vec3 top_left_;  // direction to the image corner at distance 1
    glm::vec3 step_x_;    // direction change per pixel
    glm::vec3 step_y_;
    int width_, height_;
};

}  // namespace edacrt
