#pragma once
// The camera settings a command line may give (--eye, --look-at, --up, --fov), each described
// once: the flags of `edacrt render`, `info`, `camera-rays` and the viewer
// (flags/camera_flags.h), the viewer's camera widgets and tooltips, and choose_camera() all
// come from camera_params().
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "scene/camera.h"
#include "scene/scene.h"

namespace edacrt {

/// The values given; an empty one was not given (the scene's view decides).
struct CameraOptions {
    std::vector<float> eye, look_at, up;  // X,Y,Z
    std::vector<float> fov;               // degrees, one value

    /// True when any of them was given.
    bool given() const { return !eye.empty() || !look_at.empty() || !up.empty() || !fov.empty(); }
};

/// One camera setting, described once.
struct CameraParam {
    std::string_view key;                      // flag without "--", the viewer's label
    std::string_view help;                     // flag help, the viewer's tooltip
    std::size_t count;                         // numbers: 3 (X,Y,Z) or 1
    std::vector<float> CameraOptions::*given;  // where the flag's values go
    float* (*field)(Camera&);                  // the camera's `count` floats it sets
    std::string_view ui_format;                // the viewer's number format
    float ui_min, ui_max;                      // the viewer's slider (count 1)
};

std::span<const CameraParam> camera_params();

/// default_camera(scene), overridden by each setting given. Throws InputError for an invalid
/// result (validate(Camera)).
Camera choose_camera(const Scene& scene, const CameraOptions& options);

}  // namespace edacrt
