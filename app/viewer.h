#pragma once
#include <string>
#include <vector>

#include "render/camera_options.h"
#include "render/render_settings.h"
#include "trace/tracer.h"

namespace edacrt::app {

struct ViewerOptions {
    std::string scene = "assets/cornell-box/CornellBox-Original.obj";
    Method method = Method::edacrt;
    Integrator integrator = Integrator::path;
    int spp = 1024;
    int width = 1280;  // window size
    int height = 800;
    int frames = 0;            // > 0: quit after this many frames (with --screenshot: save first)
    std::string screenshot;    // PNG of the window, taken at the last frame
    std::string script;        // UI actions (app/script.h)
    std::string assets_dir;    // where the scene list looks; default: next to the scene
    CameraOptions camera;      // --eye, --look-at, --up, --fov (as in edacrt render)
    bool hide_panels = false;  // start with the image alone (Tab / F1 toggles)
    std::string bookmarks;     // the bookmarks file; default: Bookmarks::default_path()
    // Animation (as edacrt render's flags): the spec, the time shown first, whether it plays.
    std::string animate;
    double time = 0.0;
    bool play = false;
    double speed = 1.0;
    SceneUpdate update = SceneUpdate::refit;
    double shutter = 0.0;  // > 0: motion blur
    // The animation flags given on the command line ("--speed", ...): without an animation
    // they are refused, as edacrt refuses --frames, --time and --shutter.
    std::vector<std::string> animation_flags;
};

/// Opens the window and runs until it is closed (or the frames / script end). Returns the
/// process exit code; errors are printed to stderr.
int run_viewer(const ViewerOptions& options);

}  // namespace edacrt::app
