#pragma once
// What the panels read and edit. The UI edits `ui`; the viewer turns a changed `ui` (or camera)
// into a new RenderRequest for the worker.
#include <array>
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bookmarks.h"
#include "frame_pool.h"
#include "heatmap.h"
#include "key_presses.h"
#include "layout.h"
#include "orbit_camera.h"
#include "recursion_diff.h"
#include "render/batch_capture.h"
#include "render/film.h"
#include "render/render_settings.h"
#include "render_worker.h"
#include "scene/animation.h"
#include "scene/scene.h"
#include "scene_catalog.h"
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
    double seconds = 0.0;  // update + trace
    TraceStats stats;
    std::string error;
    // How the tracer took the frame (an animation: also refit from the previous frame).
    SceneUpdate update = SceneUpdate::rebuild;
    double update_seconds = 0.0;
    int spp = 1;  // camera rays per pixel
};

/// A recorded trace of one batch of the first pass (ViewerState::batch: the camera rays, a
/// bounce, its shadow rays or the AO rays): the recursion's nodes, per-pixel counts and (for
/// the traversal debugger) one pixel's ray. Computed off the UI thread on request.
struct Analysis {
    std::shared_ptr<const TraceDetail> detail;
    std::shared_ptr<const Scene> scene;
    Camera camera;
    int width = 0, height = 0;  // of the traced image
    std::uint32_t seed = 0;
    Method method = Method::edacrt;
    EdacrtParams params;
    BatchId batch;
    RenderSettings settings;  // of the render whose first pass made the batch
    std::int64_t pixel = -1;  // the followed pixel (y * width + x), or -1
    Ray ray;                  // its first ray in the batch
    Hit hit;                  // that ray's hit (closest, or any for shadow and AO rays)
    bool followed = false;    // the pixel has a ray in the batch
    std::string error;
    // The batch's rays in this crop of the image (all of it, or a region to step through), in
    // the order the renderer traced them, and the image pixel (y * width + x) of each.
    int crop_x = 0, crop_y = 0, crop_w = 0, crop_h = 0;
    std::vector<std::uint32_t> pixels;
    // Per pixel (width * height), its rays' counts summed (deepest level: the largest): the
    // heat maps of the batch.
    std::vector<RayStats> pixel_stats;

    // The same rays traced by a second recursion (the Recursion tab's "against": a preset,
    // empty for none): its levels and nodes, and where its decisions first differ from these.
    std::string against;
    std::shared_ptr<const TraceDetail> against_detail;
    std::vector<RayStats> against_pixel_stats;
    std::vector<DecisionDifference> differences;

    /// The rays are those of a region, not the whole batch.
    bool cropped() const { return crop_w < width || crop_h < height; }

    /// The image pixel (y * width + x) of ray i of the batch.
    std::size_t pixel_of(std::size_t ray) const { return pixels[ray]; }
};

/// A region of the image as fractions of its width and height (u to the right, v down).
struct ImageRegion {
    float u0 = 0.0f, v0 = 0.0f, u1 = 0.0f, v1 = 0.0f;
    bool empty() const { return !(u1 > u0 && v1 > v0); }
};

/// The pixels of `region` in a width x height image (x, y, w, h), at least one: the pixels
/// whose centres it holds, or the nearest; an empty region is the 64x64 pixels at the centre.
std::array<int, 4> region_pixels(const ImageRegion& region, int width, int height);

/// The region in the script's and the settings' words: "U0,V0,U1,V1", or "centre" (empty).
ImageRegion parse_region(const std::string& text);
std::string region_text(const ImageRegion& region);

/// What the analysis tabs show of ViewerState::batch: its per-level statistics and per-pixel
/// counts, from the render's first pass (the camera rays) or from the analysis (another batch).
/// `detail` is null while there is none to show.
struct ShownBatch {
    const TraceDetail* detail = nullptr;
    std::span<const RayStats> pixels;  // width * height
    int width = 0, height = 0;
    std::size_t rays = 0;
    std::shared_ptr<const void> source;  // changes when the figures do (the heat map's upload)
};

/// What the heat map shows, picked every frame without computing it: per pixel of a width x
/// height image, the counts of `pixels`, less those of `minus` for B - A. `source` changes
/// when the counts do; values() computes the view's values (on upload).
struct HeatImage {
    std::span<const RayStats> pixels;  // empty: nothing to show
    std::span<const RayStats> minus;   // A's counts for B - A, else empty
    int width = 0, height = 0;
    std::shared_ptr<const void> source;

    bool difference() const { return !minus.empty(); }
    std::vector<float> values(View view) const;
};

/// Per pixel of a width x height image, the counts of the rays whose pixels[] it is: summed,
/// the deepest level the largest.
std::vector<RayStats> per_pixel_stats(std::span<const RayStats> rays,
                                      std::span<const std::uint32_t> pixels, int width, int height);

/// The RMS difference of two images of the same size, relative to the RMS of `b` (0 when b
/// is black); the change a pass made to the mean.
double relative_rms_change(const Image& a, const Image& b);

/// The per-pixel tint of the explorer (Display::upload_tint): 1 where the rays of `node` are,
/// 2 where a leaf entered no later than node `hits_up_to` found the final hit (-1: none).
std::vector<float> explorer_tint(const Analysis& analysis, std::int32_t node,
                                 std::int32_t hits_up_to);

/// The animation being played (the timeline under the image) and the per-frame times it
/// measured.
struct Playback {
    std::shared_ptr<FramePool> frames;  // null: a still scene
    double time = 0.0;                  // seconds, in [0, duration]
    bool playing = false;
    float speed = 1.0f;  // animation seconds per second of wall clock
    int play_scale = 2;  // while playing, frames render at 1/play_scale of the resolution
    bool loop = true;    // at the end, start over (else stop)
    bool motion_blur = false;
    float shutter = 1.0f / 24.0f;  // seconds around `time` the passes are spread over
    SceneUpdate update = SceneUpdate::refit;
    std::string error;    // a frame that could not be made (playback stops)
    double waited = 0.0;  // wall seconds since the last advance

    // One point per rendered frame: how long the tracer took the frame and the first pass
    // (1 spp) took, with the method that rendered it.
    struct FrameTime {
        double time;
        Method method;
        int width, height;  // of the frame (smaller while playing: play_scale)
        UpdateWork work;
        double update_seconds, pass_seconds;
    };
    std::vector<FrameTime> history;  // the newest kHistory
    static constexpr std::size_t kHistory = 600;
    double compared_time = 0.0;  // the frame the comparison (ViewerState) was measured on
};

/// A scene as read from its file, with its default view (render/default_camera.h).
struct LoadedScene {
    AnimatedScene animated;
    Camera view;
};

/// A scene being read on a thread of its own (the list, the path field, a drop): the frames go
/// on meanwhile, and the image and the Scene tab say so.
struct SceneLoad {
    std::string spec;
    std::chrono::steady_clock::time_point started;
    std::future<LoadedScene> scene;
};

struct ViewerState {
    UiSettings ui;
    bool integrator_chosen = false;  // else each scene gets path or ao (default_integrator())
    View view = View::render;
    bool heat_log = true;
    float exposure = 0.0f;
    ToneMap tone_map = ToneMap::clamp;  // of the display and the saved PNG

    std::shared_ptr<const Scene> scene;
    std::string scene_label;
    std::string scene_error;      // the last failed load (the previous scene stays)
    std::string scene_path;       // the path field
    std::string animation_spec;   // how the scene is animated (empty: still); see Playback
    std::string animation_field;  // the Scene tab's animation spec being edited
    std::string script_path;      // the script being run, if any: no output may replace it
    Playback playback;
    SceneCatalog scene_list;
    Camera scene_camera;  // for "reset view"
    OrbitCamera camera;

    std::shared_ptr<const Frame> frame;  // shown
    std::string render_error;
    bool render_answered = false;  // the worker has published a frame or error for `submitted`
    std::string resolution_error;  // the last resolution refused (too much memory)
    float accepted_resolution_scale = 1.0f;  // the slider returns here after a refusal
    std::vector<MethodTotals> comparison;    // of the scene numbered compared_scene
    bool comparing = false;                  // the render pauses meanwhile
    std::vector<std::string> pending_loads;  // from the path field, the list, drops
    std::optional<SceneLoad> loading;        // the first of them, being read
    int scene_number = 0;                    // counts the scenes taken
    int compared_scene = 0;
    bool compare_requested = false;
    int compare_spp = 1;  // camera rays per pixel of the comparison (1, 4 or 16)

    // Saving: PNG of the image region as shown (with or without overlays), PFM of the linear
    // render; the name from the scene and the time unless a path is given.
    enum class Save { none, shown, linear };
    Save save_requested = Save::none;
    bool save_overlays = true;
    std::string save_dir = "out";
    std::string save_path;   // empty: save_dir/SCENE-TIME.png
    std::string save_error;  // why the last save failed (a script fails on it)
    std::string status;      // one line of feedback (saved, loaded, ...)

    // Convergence of the render in progress: per pass, the RMS change of the mean image from
    // the previous pass, relative to the image's RMS (restarted with every new request).
    struct ConvergencePoint {
        double seconds;
        int spp;
        double change;
    };
    std::vector<ConvergencePoint> convergence;

    // Layout: what the last frame drew where (app/layout.h).
    Layout layout;
    bool panels_hidden = false;   // Tab / F1
    float font_scale = 1.0f;      // of the panels, times content_scale (Ctrl +/-)
    float content_scale = 1.0f;   // the monitor's (the window system's DPI scale)
    float analysis_share = 0.0f;  // LayoutOptions::analysis_share (the dragged split)
    bool dragging_split = false;  // the analysis's title bar is being dragged
    bool analysis_open = true;
    bool show_help = false;                // H / ?
    bool all_columns = false;              // the Statistics table's detail columns too
    KeyPresses keys;                       // since the frame began (the window's key events)
    std::vector<std::string> select_tabs;  // tabs to bring forward (the script's `tab NAME`)
    std::vector<PanelPlacement> placements;
    std::vector<std::string> layout_problems;  // of the last frame (the script's check-layout)
    // What the last frame drew (the script's waits and `layout FILE`): widgets the panels
    // report (named "Tab/widget", tab headers "Tab/tab"), the tabs whose contents were drawn,
    // the error messages shown.
    std::vector<NamedRect> items;
    std::vector<std::string> tabs_open;
    std::vector<std::string> errors_shown;
    float window_width = 0.0f, window_height = 0.0f;  // ImGui's units (window coordinates)
    float framebuffer_scale_x = 1.0f, framebuffer_scale_y = 1.0f;  // pixels per unit

    // Camera panel.
    int fly_speed_step = 0;  // fly_speed(): +/- keys
    Bookmarks bookmarks;
    std::string bookmarks_path;
    std::string bookmark_name;
    std::string command_line;  // the `edacrt render` command of the view

    // The batch Statistics, Heat map, Recursion and Traversal analyse (camera: the render's own
    // statistics; another: recorded by the analysis job).
    BatchId batch;
    // Recursion explorer and traversal debugger.
    std::shared_ptr<const Analysis> analysis;
    bool analysis_running = false;
    bool analysis_requested = false;
    std::int64_t follow_pixel = -1;  // the debugger's pixel, for the next analysis
    bool picking = false;            // clicks on the image pick the debugger's pixel
    int explorer_level = 0;
    std::int32_t explorer_node = -1;  // selected node (its candidate splits are shown)
    std::int32_t hovered_candidate = -1;
    bool explorer_crop = false;    // record the rays of explorer_region, not the whole batch
    ImageRegion explorer_region;   // empty: 64x64 pixels at the centre
    bool region_picking = false;   // the next left drag on the image sets explorer_region
    std::string against;           // a preset the recording is compared with (empty: none)
    HeatOf heat_of = HeatOf::a;    // the heat map of A, B or B - A (with such a recording)
    bool explorer_tint = true;     // tint the selected node's pixels
    bool stepping = false;         // step-through: the selected node follows `step`
    int step = 0;                  // nodes entered so far, in the recursion's order
    bool step_playing = false;     // step-through advances by itself...
    float step_rate = 10.0f;       // ...this many nodes per second
    double step_carry = 0.0;       // the part of a node played but not yet shown
    bool recursion_shown = false;  // the Recursion tab was drawn this frame
    bool analysis_stale = false;   // recorded for another view, parameters or scene
    RenderRequest submitted;       // what the render in progress was asked for
};

/// Path tracing for a scene with emitters; ambient occlusion for one without, which path
/// tracing lights only by the sky through its openings (Sponza's first passes are almost
/// black), while AO shows its shapes at once, through an any-hit batch the analysis can show.
Integrator default_integrator(const Scene& scene);

/// Step-through playing at `rate` nodes per second, `dt` seconds after the last frame: the node
/// to show of nodes 0..last, `carry` keeping the fraction of a node between frames. Returns
/// the step; playing stops (`playing` false) at the last node.
int advance_step(int step, int last, float rate, double dt, double& carry, bool& playing);

/// The font scales Ctrl +/- steps through (font_scale), and their bounds.
inline constexpr float kMinFontScale = 0.5f, kMaxFontScale = 3.0f, kFontScaleStep = 1.125f;

/// The font scale after `steps` presses of Ctrl + (negative: Ctrl -), within the bounds.
float step_font_scale(float scale, int steps);

/// Moves the animation to `t` (wrapped into [0, duration] when looping, else clamped; the
/// end stops playback; an animation without duration does not play): the state's scene
/// becomes that frame. On an error the scene stays,
/// playback stops and the error shows.
void seek(ViewerState& state, double t);

/// Called once per UI frame, `dt` seconds after the last: while playing, once the shown frame
/// has its first full-resolution pass (`frame_done`), advances the time by the wall clock
/// since the last advance times the speed (not counting time the render was paused or
/// comparing methods). Frames are never skipped half-rendered, so a slow
/// method plays fewer frames, each at its real time.
void advance_playback(ViewerState& state, bool frame_done, double dt);

/// Play or pause (the timeline's button, Space); playing from the end without a loop starts
/// over from 0.
void toggle_play(ViewerState& state);

/// Adds a rendered frame's times to the playback history (once per frame: its first
/// full-resolution pass; another view of the same time and method is not added).
void record_frame_time(ViewerState& state, const Frame& frame, Method method);

/// Why the EDACRT parameter cannot change the render under the method, the other parameters
/// and the threads of `ui` (param_no_effect_reason(), and the choices dacrt makes); empty when
/// it can.
std::string param_inert_reason(const UiSettings& ui, const ParamInfo& info);

/// Applies a script's `set KEY VALUE`: a setting of viewer_settings() (app/settings_table.h),
/// an EDACRT parameter (its flag without "--"), a preset, or an action (scene, animate, the
/// explorer's level, node, crop, region and step, the analysed batch). Throws InputError.
void apply_setting(ViewerState& state, const std::string& key, const std::string& value);

/// The heat map of the state's view: the shown batch's (A), or, with a recording compared
/// with another recursion (not stale), B's or B - A as heat_of asks.
HeatImage heat_image(const ViewerState& state);

/// The batch the analysis tabs show (ShownBatch): the first pass's camera rays from the shown
/// frame, another batch from a current analysis of it.
ShownBatch shown_batch(const ViewerState& state);

/// True when the recording was made for another scene, view, size, seed, method or parameters
/// than the render in progress, or another batch than `batch` (of other render settings).
bool analysis_stale(const Analysis& analysis, const RenderRequest& submitted, BatchId batch);

}  // namespace edacrt::app
