#pragma once
// The viewer's camera: orbit around a target, turn about the eye, pan, zoom (mouse), fly (WASD).
// Pure math, no UI.
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

    /// Drag by (dx, dy) pixels: orbit about the target (the eye moves), look (first person: the
    /// eye stays, the view turns as much as an orbit would turn it), pan, in a view `height`
    /// tall.
    void orbit(float dx, float dy);
    void look(float dx, float dy);
    void pan(float dx, float dy, float height);
    /// Mouse wheel: positive moves closer.
    void zoom(float steps);
    /// Moves eye and target together by `distance` along forward/right/up (each -1, 0 or 1).
    void fly(float forward, float right, float up, float distance);
    /// Orbits about `point` from now on: the eye stays, the target becomes `point`.
    void orbit_about(const glm::vec3& point);

    Camera camera() const;

  private:
    /// The unit vector from the target to the eye.
    glm::vec3 direction() const;
    /// Takes `next` when its camera is valid; else throws InputError naming `what`.
    void commit(const OrbitCamera& next, const char* what);

    glm::vec3 target_{0.0f};
    float distance_ = 1.0f;
    float yaw_ = 0.0f;    // around the up axis, radians
    float pitch_ = 0.0f;  // above the horizontal, radians
    glm::vec3 up_{0.0f, 1.0f, 0.0f};
    float vfov_degrees_ = 45.0f;
};

/// What a drag on the image does, by mouse button (0 left, 1 right, 2 middle): left orbits, or
/// with the eye inside the scene's box (an interior, whose look-at point is often a far wall an
/// orbit would swing the eye out through) looks; right looks; middle, or left with Shift, pans.
enum class DragAction { orbit, look, pan };
DragAction drag_action(int button, bool shift, bool eye_inside_scene);

/// WASD flight speed in world units per second: a tenth of the scene box's diagonal (it crosses
/// the scene in ten seconds whatever its units), times 1.25 per step (+/- keys).
float fly_speed(const Aabb& scene_box, int step);
constexpr int kFlySpeedSteps = 20;  // steps go from -20 to 20 (0.01x to 87x)

}  // namespace edacrt::app
