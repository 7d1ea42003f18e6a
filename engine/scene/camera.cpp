#include "scene/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <string>

#include "util/error.h"

namespace edacrt {

namespace {

/// How far frame_box() backs off from the centre: until the bounding sphere fits the vertical
/// field of view.
float framing_distance(const Aabb& box, float vfov_degrees) {
    const float radius = std::max(0.5f * glm::length(box.extent()), 1e-6f);
    return radius / std::sin(0.5f * glm::radians(vfov_degrees));
}

}  // namespace

const char* framing_side(const Aabb& box, float vfov_degrees) {
    const glm::vec3 extent = box.extent();
    // Clearly deeper: a box as deep as wide (the Buddha's, 0.81 by 0.81) keeps the front view.
    if (!(extent.z > 1.25f * extent.x)) return "+z";
    // Not where the eye would round onto the centre (a tiny box at x = 1e30).
    const float x = box.center().x;
    return x + framing_distance(box, vfov_degrees) != x ? "+x" : "+z";
}

Camera frame_box(const Aabb& box, float vfov_degrees) {
    Camera camera;
    camera.vfov_degrees = vfov_degrees;
    camera.look_at = box.center();
    const glm::vec3 side = framing_side(box, vfov_degrees)[1] == 'x' ? glm::vec3(1.0f, 0.0f, 0.0f)
                                                                     : glm::vec3(0.0f, 0.0f, 1.0f);
    camera.eye = camera.look_at + side * framing_distance(box, vfov_degrees);
    return camera;
}

namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The orthonormal frame of the view, in the float arithmetic the projection uses.
struct ViewBasis {
    glm::vec3 forward, right, up;
};

/// Up scaled to a largest component of 1 (exact for the usual unit axes), so that a huge up
/// vector cannot overflow the cross product's length.
glm::vec3 scaled_up(const Camera& camera) {
    const glm::vec3 a = glm::abs(camera.up);
    return camera.up / std::max({a.x, a.y, a.z});
}

ViewBasis view_basis(const Camera& camera) {
    const glm::vec3 forward = glm::normalize(camera.look_at - camera.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, scaled_up(camera)));
    return {forward, right, glm::cross(right, forward)};
}

}  // namespace

void validate(const Camera& camera) {
    if (!finite(camera.eye) || !finite(camera.look_at) || !finite(camera.up))
        throw InputError("camera: eye, look-at and up must be finite");
    if (!(camera.vfov_degrees > 0.0f && camera.vfov_degrees < 180.0f))
        throw InputError("camera: vertical field of view must be in (0, 180) degrees, got " +
                         std::to_string(camera.vfov_degrees));
    const glm::vec3 view = camera.look_at - camera.eye;
    if (view == glm::vec3(0.0f)) throw InputError("camera: eye and look-at are the same point");
    // Finite inputs can still overflow: eye - look_at past 3.4e38, or a length past 1.8e19
    // (whose square overflows, so normalize gives 0 and then NaN), or underflow (a distance
    // near 1e-19). Every later step compares NaN as false, so the frame itself is checked.
    const ViewBasis basis = view_basis(camera);
    if (!finite(view) || !finite(basis.forward) || glm::length(basis.forward) < 0.5f)
        throw InputError(
            "camera: the view direction cannot be normalised in float: eye and look-at are "
            "too far apart or too close");
    const glm::vec3 up = scaled_up(camera);
    if (!finite(up) || glm::length(glm::cross(basis.forward, up)) <= 1e-6f * glm::length(up) ||
        !finite(basis.right) || !finite(basis.up))
        throw InputError("camera: up vector is zero or parallel to the view direction");
}

PinholeProjection::PinholeProjection(const Camera& camera, int width, int height)
    : eye_(camera.eye), width_(width), height_(height) {
    validate(camera);
    const auto [forward, right, up] = view_basis(camera);
    const float half_height = std::tan(0.5f * glm::radians(camera.vfov_degrees));
    const float half_width = half_height * float(width) / float(height);
    forward_ = forward;
    right_ = right;
    up_ = up;
    half_width_ = half_width;
    half_height_ = half_height;
    top_left_ = forward - half_width * right + half_height * up;
    step_x_ = (2.0f * half_width / float(width)) * right;
    step_y_ = (-2.0f * half_height / float(height)) * up;
}

std::optional<glm::vec2> PinholeProjection::pixel(const glm::vec3& point) const {
    const glm::vec3 d = point - eye_;
    const float z = glm::dot(d, forward_);
    if (!(z > 0.0f)) return std::nullopt;
    const float u = glm::dot(d, right_) / z, v = glm::dot(d, up_) / z;
    return glm::vec2((u + half_width_) / (2.0f * half_width_) * float(width_),
                     (half_height_ - v) / (2.0f * half_height_) * float(height_));
}

Ray PinholeProjection::ray(float x, float y) const {
    Ray ray;
    ray.org = eye_;
    ray.dir = glm::normalize(top_left_ + x * step_x_ + y * step_y_);
    return ray;
}

std::vector<Ray> PinholeProjection::pixel_centre_rays() const {
    std::vector<Ray> rays;
    rays.reserve(std::size_t(width_) * std::size_t(height_));
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) rays.push_back(ray(float(x) + 0.5f, float(y) + 0.5f));
    return rays;
}

}  // namespace edacrt
