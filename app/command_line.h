#pragma once
// The `edacrt render` command that reproduces the viewer's view: scene, method, integrator,
// samples, size, seed, exact camera (floats printed so they read back bit for bit), tone map
// every EDACRT parameter that differs from its default, and the animation time.
#include <string>

#include "render/film.h"
#include "render/render_settings.h"
#include "scene/camera.h"
#include "trace/tracer.h"

namespace edacrt::app {

struct ViewCommand {
    std::string scene;  // a scene, or an animation that names its own geometry (FILE.json)
    // An animation: its spec (of the scene, or empty when `scene` is the animation), the time
    // shown, how the tracer takes frames, the motion blur shutter (0: none).
    bool animated = false;
    std::string animation;
    double time = 0.0;
    SceneUpdate update = SceneUpdate::refit;
    double shutter = 0.0;
    Method method = Method::edacrt;
    EmbreeMode embree_mode = kDefaultEmbreeMode;
    EdacrtParams params;
    RenderSettings settings;
    Camera camera;
    int spp = 1;
    float exposure = 0.0f;
    ToneMap tone_map = ToneMap::clamp;
    std::string out = "out/view.png";
};

/// One shell line (arguments quoted where needed).
std::string render_command_line(const ViewCommand& view);

}  // namespace edacrt::app
