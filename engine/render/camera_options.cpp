#include "render/camera_options.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "render/default_camera.h"
#include "util/error.h"

namespace edacrt {
namespace {

const std::array<CameraParam, 4> kCameraParams = {{
    {"eye",
     "camera position X,Y,Z (default: the scene's own camera; else inside an interior, near the "
     "middle of the floor; else framing the scene from +z, or +x if it is clearly deeper than "
     "wide)",
     3, &CameraOptions::eye, [](Camera& c) { return glm::value_ptr(c.eye); }, "%.4g", 0.0f, 0.0f},
    {"look-at", "point the camera looks at X,Y,Z", 3, &CameraOptions::look_at,
     [](Camera& c) { return glm::value_ptr(c.look_at); }, "%.4g", 0.0f, 0.0f},
    {"up", "camera up vector X,Y,Z", 3, &CameraOptions::up,
     [](Camera& c) { return glm::value_ptr(c.up); }, "%.4g", 0.0f, 0.0f},
    {"fov", "vertical field of view in degrees", 1, &CameraOptions::fov,
     [](Camera& c) { return &c.vfov_degrees; }, "%.1f deg", 5.0f, 150.0f},
}};

}  // namespace

std::span<const CameraParam> camera_params() { return kCameraParams; }

Camera choose_camera(const Scene& scene, const CameraOptions& options) {
    const Camera fallback = default_camera(scene);
    Camera camera = fallback;
    for (const CameraParam& param : kCameraParams) {
        const std::vector<float>& values = options.*param.given;
        if (values.size() >= param.count)
            std::copy_n(values.begin(), param.count, param.field(camera));
    }
    try {
        validate(camera);
    } catch (const InputError& e) {
        // The user gave no such camera: name the scene and the flags that replace its view.
        if (scene.camera) throw;
        try {
            validate(fallback);
        } catch (const InputError&) {
            const auto finite3 = [](glm::vec3 v) {
                return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
            };
            const bool finite = finite3(fallback.eye) && finite3(fallback.look_at);
            throw InputError(
                scene.source + ": the default camera from its bounds is " +
                (finite ? "not valid (" + std::string(e.what()) + ")" : std::string("not finite")) +
                " (coordinates near the float limit); give --eye and --look-at");
        }
        throw;
    }
    return camera;
}

}  // namespace edacrt
