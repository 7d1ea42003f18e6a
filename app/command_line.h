#pragma once
// The `edacrt render` command that reproduces the viewer's view: scene, method, integrator,
// samples, size, seed, exact camera (floats printed so they read back bit for bit), tone map
// and every EDACRT parameter that differs from its default.
#include <string>

#include "render/render_settings.h"
#include "scene/camera.h"
#include "trace/tracer.h"

namespace edacrt::app {

struct ViewCommand {
    std::string scene;
    Method method = Method::edacrt;
    EmbreeMode embree_mode = kDefaultEmbreeMode;
    EdacrtParams params;
    RenderSettings settings;
    Camera camera;
    int spp = 1;
    float exposure = 0.0f;
    std::string tone_map = "clamp";
    std::string out = "out/view.png";
};

/// One shell line (arguments quoted where needed).
std::string render_command_line(const ViewCommand& view);

}  // namespace edacrt::app
