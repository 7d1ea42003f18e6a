#pragma once
// What an image file's header records about the render that made it (EXR has room for it),
// the same from the CLI and the viewer.
#include <string>

#include "render/exr_image.h"
#include "scene/camera.h"

namespace edacrt {

struct RenderDescription {
    std::string software;  // "edacrt render", ...
    std::string scene, method, integrator;
    int spp = 0;
    std::uint32_t seed = 0;
    double seconds = 0.0;  // rendering time
    Camera camera;
};

/// Name and value pairs: software, scene, method, integrator, spp, seed, renderSeconds, and the
/// camera as cameraEye, cameraLookAt, cameraUp ("x,y,z") and cameraVerticalFovDegrees.
ImageMetadata render_metadata(const RenderDescription& render);

}  // namespace edacrt
