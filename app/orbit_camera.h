#pragma once
// The viewer's camera: orbit around a target, pan, zoom (mouse), fly (WASD). Pure math, no UI.
// Every change keeps the camera valid (edacrt::validate(Camera), as the CLI checks it): one
// that would leave float range (orbit 1e40 1e40, a pan past 3e38) throws InputError and
// leaves the camera as it was, so no NaN view is rendered, written or bookmarked.
#include <glm/vec3.hpp>

#include "geometry/aabb.h"
#include "scene/camera.h"

namespace edacrt::app {

class OrbitCamera {
  public:
    /// Starts from `camera` (e.g. the scene's own), orbiting its look-at point.
    void reset(const Camera& camera);
    // Each change below throws InputError, the camera unchanged, when its result is not valid.

    /// Drag by (dx, dy) pixels: orbit (left button), pan (right/middle), in a view `height` tall.
    void orbit(float dx, float dy);
    void pan(float dx, float dy, float height);
    /// Mouse wheel: positive moves closer.
    void zoom(float steps);
    /// Moves eye and target together: forward/right/up in units of the orbit distance per second.
    void fly(float forward, float right, float up, float seconds);

    Camera camera() const;

  private:
    /// Takes `next` when its camera is valid; else throws InputError naming `what`.
    void commit(const OrbitCamera& next, const char* what);

    glm::vec3 target_{0.0f};
    float distance_ = 1.0f;
    float yaw_ = 0.0f;    // around the up axis, radians
    float pitch_ = 0.0f;  // above the horizontal, radians
    glm::vec3 up_{0.0f, 1.0f, 0.0f};
    float vfov_degrees_ = 45.0f;
};

}  // namespace edacrt::app
