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

Camera OrbitCamera::camera() const {
    const glm::vec3 x = any_perpendicular(up_), z = glm::cross(x, up_);
    const glm::vec3 dir =
        std::cos(pitch_) * (std::sin(yaw_) * x + std::cos(yaw_) * z) + std::sin(pitch_) * up_;
    return Camera{target_ + distance_ * dir, target_, up_, vfov_degrees_};
}

void OrbitCamera::orbit(float dx, float dy) {
    OrbitCamera next = *this;
    next.yaw_ -= dx * 0.008f;
    next.pitch_ = std::clamp(pitch_ + dy * 0.008f, -kMaxPitch, kMaxPitch);
    commit(next, "orbit");
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

void OrbitCamera::fly(float forward, float right, float up, float seconds) {
    const Camera c = camera();
    const glm::vec3 f = glm::normalize(c.look_at - c.eye);
    const glm::vec3 r = glm::normalize(glm::cross(f, up_));
    OrbitCamera next = *this;
    next.target_ += (forward * f + right * r + up * up_) * (distance_ * seconds);
    commit(next, "fly");
}

}  // namespace edacrt::app
