#pragma once
// The `edacrt render` command that reproduces the viewer's view: scene, method, integrator,
// samples, size, seed, exact camera (floats printed so they read back bit for bit), tone map
// every EDACRT parameter that differs from its default, and the animation time. It runs as
// pasted from any folder: the program and the scene are absolute paths, every word quoted
// for the shell where needed.
#include <filesystem>
#include <string>

#include "render/film.h"
#include "render/render_settings.h"
#include "scene/camera.h"
#include "trace/tracer.h"

namespace edacrt::app {

struct ViewCommand {
    std::string program = "edacrt";  // edacrt_program(): absolute, or found on PATH
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

/// One shell line (arguments quoted where needed; a relative scene path made absolute against
/// the current folder).
std::string render_command_line(const ViewCommand& view);

/// The edacrt program beside `viewer` (the build and the install put both in one folder), as
/// an absolute path; "edacrt", to be found on PATH, when there is none.
std::string edacrt_program(const std::filesystem::path& viewer);

/// This process's executable (/proc/self/exe); empty where that cannot be read.
std::filesystem::path this_executable();

}  // namespace edacrt::app
