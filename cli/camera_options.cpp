#include "camera_options.h"

#include "render/default_camera.h"

namespace edacrt::cli {
namespace {

glm::vec3 to_vec3(const std::vector<float>& v) { return {v[0], v[1], v[2]}; }

}  // namespace

void add_camera_options(CLI::App& command, CameraOptions& o) {
    const auto vec3_option = [&](const char* name, std::vector<float>& target, const char* what) {
        command.add_option(name, target, what)->expected(3)->delimiter(',');
    };
    vec3_option("--eye", o.eye,
                "camera position X,Y,Z (default: the scene's own camera; else inside an interior, "
                "near the middle of the floor; else framing the scene from +z)");
    vec3_option("--look-at", o.look_at, "point the camera looks at X,Y,Z");
    vec3_option("--up", o.up, "camera up vector X,Y,Z");
    command.add_option("--fov", o.fov, "vertical field of view in degrees");
}

void add_image_size_options(CLI::App& command, int& width, int& height) {
    command.add_option("--width", width, "image width in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    command.add_option("--height", height, "image height in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
}

Camera choose_camera(const Scene& scene, const CameraOptions& o) {
    Camera camera = default_camera(scene);
    if (!o.eye.empty()) camera.eye = to_vec3(o.eye);
    if (!o.look_at.empty()) camera.look_at = to_vec3(o.look_at);
    if (!o.up.empty()) camera.up = to_vec3(o.up);
    if (o.fov) camera.vfov_degrees = *o.fov;
    validate(camera);
    return camera;
}

}  // namespace edacrt::cli
