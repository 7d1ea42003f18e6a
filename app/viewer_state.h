#pragma once
// What the panels read and edit. The UI edits `ui`; the viewer turns a changed `ui` (or camera)
// into a new RenderRequest for the worker.
#include <memory>
#include <string>
#include <vector>

#include "heatmap.h"
#include "orbit_camera.h"
#include "render/render_settings.h"
#include "render_worker.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace edacrt::app {

struct UiSettings {
    Method method = Method::edacrt;
    EmbreeMode embree_mode = kDefaultEmbreeMode;
    EdacrtParams params;
    Integrator integrator = Integrator::path;
    PrimaryShading primary = PrimaryShading::eye_light;
    int max_depth = 8;
    int ao_samples = 4;
    int spp_target = 1024;
    float resolution_scale = 1.0f;  // of the window's framebuffer
    int threads = 0;
    int seed = 0;
    bool paused = false;

    bool operator==(const UiSettings&) const = default;
};

/// Per-method totals of the current view's camera rays, for comparison with the chosen method.
struct MethodTotals {
    Method method;
    double seconds = 0.0;
    TraceStats stats;
    std::string error;
};

struct ViewerState {
    UiSettings ui;
    View view = View::render;
    bool heat_log = true;
    float exposure = 0.0f;
    int tone_map = 0;  // clamp, Reinhard, ACES

    std::shared_ptr<const Scene> scene;
    std::string scene_label;
    std::string scene_error;  // the last failed load (the previous scene stays)
    std::string scene_path;   // the path field
    std::vector<std::string> scene_list;
    Camera scene_camera;  // for "reset view"
    OrbitCamera camera;

    std::shared_ptr<const Frame> frame;  // shown
    std::string render_error;
    std::vector<MethodTotals> comparison;
    std::vector<std::string> pending_loads;  // from the path field, the list, drops
    bool compare_requested = false;
    bool save_requested = false;
    std::string save_path = "out/viewer.png";
    std::string status;  // one line of feedback (saved, loaded, ...)
};

// The panels, one file each under panels/.
void draw_render_panel(ViewerState& state);
void draw_params_panel(ViewerState& state);
void draw_stats_panel(ViewerState& state);
void draw_heatmap_panel(ViewerState& state, float heat_max);

}  // namespace edacrt::app
