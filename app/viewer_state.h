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

/// A recorded trace of the current view's pixel-centre camera rays: the recursion's nodes and
/// (for the traversal debugger) one pixel's path. Computed off the UI thread on request.
struct Analysis {
    std::shared_ptr<const TraceDetail> detail;
    Camera camera;
    int width = 0, height = 0;  // of the traced image
    Method method = Method::edacrt;
    std::int64_t pixel = -1;  // the followed pixel (y * width + x), or -1
    Hit hit;                  // its closest hit
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
    std::string resolution_error;            // the last resolution refused (too much memory)
    float accepted_resolution_scale = 1.0f;  // the slider returns here after a refusal
    std::vector<MethodTotals> comparison;
    std::vector<std::string> pending_loads;  // from the path field, the list, drops
    bool compare_requested = false;
    bool save_requested = false;
    std::string save_path = "out/viewer.png";
    std::string status;  // one line of feedback (saved, loaded, ...)

    // Recursion explorer and traversal debugger.
    std::shared_ptr<const Analysis> analysis;
    bool analysis_running = false;
    bool analysis_requested = false;
    std::int64_t follow_pixel = -1;  // the debugger's pixel, for the next analysis
    bool picking = false;            // the next click on the image picks the debugger's pixel
    int explorer_level = 0;
    std::int32_t explorer_node = -1;  // selected node (its candidate splits are shown)
    std::int32_t hovered_candidate = -1;
    std::vector<std::pair<std::string, bool>> collapse_panels;  // from the script: name, closed
};

// The panels, one file each under panels/.
void draw_render_panel(ViewerState& state);
void draw_params_panel(ViewerState& state);
void draw_stats_panel(ViewerState& state);
void draw_heatmap_panel(ViewerState& state, float heat_max);
void draw_recursion_panel(ViewerState& state);
void draw_traversal_panel(ViewerState& state);

/// Draws a box's projected edges over the image (background draw list).
void draw_box_overlay(const Analysis& analysis, const Aabb& box, unsigned colour,
                      float thickness = 1.0f);

}  // namespace edacrt::app
