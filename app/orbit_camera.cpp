#include "orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <string>

#include "util/error.h"

namespace edacrt::app {
namespace {

constexpr float kMaxPitch = 1.55f;  // just under 90 degrees: keeps `up` usable
constexpr float kRadiansPerPixel = 0.008f;

/// A unit vector perpendicular to the unit vector up.
glm::vec3 any_perpendicular(glm::vec3 up) {
    const glm::vec3 a = std::abs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(up, a));
}

}  // namespace

void OrbitCamera::commit(const OrbitCamera& next, const char* what) {
    try {
        validate(next.camera());
    } catch (const InputError& e) {
        throw InputError(std::string(what) + " refused, the view is unchanged: " + e.what());
    }
    *this = next;
}

void OrbitCamera::reset(const Camera& camera) {
    try {
        validate(camera);
    } catch (const InputError& e) {
        throw InputError(std::string("view refused, the view is unchanged: ") + e.what());
    }
    OrbitCamera next = *this;
    next.target_ = camera.look_at;
    next.up_ = glm::normalize(camera.up);
    next.vfov_degrees_ = camera.vfov_degrees;
    const glm::vec3 offset = camera.eye - camera.look_at;
    next.distance_ = std::max(glm::length(offset), 1e-6f);
    const glm::vec3 dir = offset / next.distance_;
    next.pitch_ = std::asin(std::clamp(glm::dot(dir, next.up_), -1.0f, 1.0f));
    const glm::vec3 x = any_perpendicular(next.up_), z = glm::cross(x, next.up_);
    next.yaw_ = std::atan2(glm::dot(dir, x), glm::dot(dir, z));
    commit(next, "view");  // valid, yet its eye rebuilt from look-at and distance may overflow
}

glm::vec3 OrbitCamera::direction() const {
    const glm::vec3 x = any_perpendicular(up_), z = glm::cross(x, up_);
    return std::cos(pitch_) * (std::sin(yaw_) * x + std::cos(yaw_) * z) + std::sin(pitch_) * up_;
}

Camera OrbitCamera::camera() const {
    return Camera{target_ + distance_ * direction(), target_, up_, vfov_degrees_};
}

void OrbitCamera::orbit(float dx, float dy) {
    OrbitCamera next = *this;
    next.yaw_ -= dx * kRadiansPerPixel;
    next.pitch_ = std::clamp(pitch_ + dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
    commit(next, "orbit");
}

void OrbitCamera::look(float dx, float dy) {
    // The same turn of the view direction as orbit(), about the eye: the target moves.
    const glm::vec3 eye = camera().eye;
    OrbitCamera next = *this;
    next.yaw_ -= dx * kRadiansPerPixel;
    next.pitch_ = std::clamp(pitch_ + dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
    next.target_ = eye - distance_ * next.direction();
    commit(next, "look");
}

void OrbitCamera::orbit_about(const glm::vec3& point) {
    Camera c = camera();
    c.look_at = point;
    reset(c);  // refused, the camera unchanged, for a point at the eye or straight above it
}

void OrbitCamera::pan(float dx, float dy, float height) {
    const Camera c = camera();
    const glm::vec3 forward = glm::normalize(c.look_at - c.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, up_));
    const glm::vec3 up = glm::cross(right, forward);
    // One pixel at the target's distance.
    const float pixel =
        2.0f * distance_ * std::tan(glm::radians(vfov_degrees_) * 0.5f) / std::max(height, 1.0f);
    OrbitCamera next = *this;
    next.target_ += (-dx * right + dy * up) * pixel;
    commit(next, "pan");
}

void OrbitCamera::zoom(float steps) {
    OrbitCamera next = *this;
    next.distance_ = std::max(distance_ * std::pow(0.9f, steps), 1e-6f);
    commit(next, "zoom");
}

void OrbitCamera::fly(float forward, float right, float up, float distance) {
    const Camera c = camera();
    const glm::vec3 f = glm::normalize(c.look_at - c.eye);
    const glm::vec3 r = glm::normalize(glm::cross(f, up_));
    OrbitCamera next = *this;
    next.target_ += (forward * f + right * r + up * up_) * distance;
    commit(next, "fly");
}

DragAction drag_action(int button, bool shift, bool eye_inside_scene) {
    if (button == 2 || (button == 0 && shift)) return DragAction::pan;
    if (button == 1 || eye_inside_scene) return DragAction::look;
    return DragAction::orbit;
}

float fly_speed(const Aabb& scene_box, int step) {
    const float diagonal = scene_box.empty() ? 1.0f : glm::length(scene_box.extent());
    return 0.1f * (diagonal > 0.0f ? diagonal : 1.0f) *
           std::pow(1.25f, float(std::clamp(step, -kFlySpeedSteps, kFlySpeedSteps)));
}

}  // namespace edacrt::app
