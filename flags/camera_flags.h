#pragma once
// The camera and image-size flags of the commands that make camera rays, in both tools (edacrt
// and edacrt_viewer): generated from the camera's descriptions (render/camera_options.h).
#include <CLI/CLI.hpp>

#include "render/camera_options.h"

namespace edacrt::flags {

/// --eye, --look-at, --up and --fov, one per camera_params() entry.
void add_camera_options(CLI::App& command, CameraOptions& options);

/// --width and --height of the image, in pixels (1 to 16384).
void add_image_size_options(CLI::App& command, int& width, int& height);

}  // namespace edacrt::flags
