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

/// default_camera(scene), overridden flag by flag.
/// Throws InputError for an invalid result.
Camera choose_camera(const Scene& scene, const CameraOptions& options);

}  // namespace edacrt::cli
