#pragma once
#include <string>

#include "render/camera_options.h"
#include "settings_table.h"

namespace edacrt::app {

struct ViewerOptions {
    std::string scene = "assets/cornell-box/CornellBox-Original.obj";
    GivenSettings settings;  // --method, --spp, ...: viewer_settings()' flags
    int width = 1280;        // window size
    int height = 800;
    int frames = 0;            // > 0: quit after this many frames (with --screenshot: save first)
    std::string screenshot;    // PNG of the window, taken at the last frame
    std::string script;        // UI actions (app/script.h)
    std::string assets_dir;    // where the scene list looks; default: next to the scene
    CameraOptions camera;      // --eye, --look-at, --up, --fov (as in edacrt render)
    bool hide_panels = false;  // start with the image alone (Tab / F1 toggles)
    std::string bookmarks;     // the bookmarks file; default: Bookmarks::default_path()
    std::string animate;       // the animation's spec (as edacrt render's --animate)
};

/// Opens the window and runs until it is closed (or the frames / script end). Returns the
/// process exit code; errors are printed to stderr.
int run_viewer(const ViewerOptions& options);

}  // namespace edacrt::app
