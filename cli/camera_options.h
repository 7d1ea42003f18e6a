#pragma once
// The camera flags of commands that make camera rays.
#include <CLI/CLI.hpp>
#include <optional>
#include <vector>

#include "scene/scene.h"

namespace edacrt::cli {

struct CameraOptions {
    std::vector<float> eye, look_at, up;
    std::optional<float> fov;
};

void add_camera_options(CLI::App& command, CameraOptions& options);

/// --width and --height of the image, in pixels (1 to 16384).
void add_image_size_options(CLI::App& command, int& width, int& height);

/// default_camera(scene), overridden flag by flag.
/// Throws InputError for an invalid result.
Camera choose_camera(const Scene& scene, const CameraOptions& options);

}  // namespace edacrt::cli
