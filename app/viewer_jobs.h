#pragma once
// The viewer's work that needs no window (tested headless): loading scenes into the state,
// turning the settings into a render request that fits in memory, the engine jobs run off the
// UI thread (comparing methods, recording the recursion) and output names.
#include <memory>
#include <string>
#include <vector>

#include "render/camera_options.h"
#include "render_worker.h"
#include "util/error.h"
#include "viewer_state.h"

namespace edacrt::app {

/// Loads a scene into the state, animated as `animation` says (a spec of
/// load_animated_scene(); an animation file or OBJ sequence may be given as `spec` itself), at
/// time 0; on failure keeps the previous one and shows the error. The camera flags override
/// the scene's view (render/camera_options.h); `keep_view` keeps the current camera (a new
/// animation of the same scene).
void load_into(ViewerState& state, const std::string& spec,
               const CameraOptions& flags = CameraOptions{}, const std::string& animation = "",
               bool keep_view = false);

/// Once a frame: takes the scene read on its own thread, if it is done (the rules of
/// load_into(), without camera flags), then starts reading the next scene asked for.
void poll_loads(ViewerState& state);

/// The request for the current settings; width x height: the image region in framebuffer
/// pixels.
RenderRequest make_request(const ViewerState& state, int width, int height);

/// A new resolution is taken only if the render fits in memory; otherwise the error shows
/// (printed once) and the previous resolution stays, the slider included. Returns false when
/// there is no resolution to render at yet.
bool fit_resolution(ViewerState& state, RenderRequest& request, const RenderRequest& submitted);

/// The camera rays the methods are compared on: the pixel centres at 1 spp, else `spp`
/// jittered rays per pixel, as `edacrt bench` makes them. Throws InputError when their trace
/// would take more than half the memory limit (the paused render keeps the rest).
std::vector<Ray> compare_rays(const Camera& camera, int width, int height, int spp,
                              std::uint32_t seed);

/// Every method on compare_rays(), once `worker` is idle (the caller pauses it): the median of
/// three update + trace. The update is set_scene(); given the `previous` frame of an
/// animation, also bvh's refit and embree's dynamic commit and refit from it.
std::vector<MethodTotals> compare_methods(std::shared_ptr<const Scene> scene,
                                          std::shared_ptr<const Scene> previous, Camera camera,
                                          int width, int height, int spp, std::uint32_t seed,
                                          EdacrtParams params, const RenderWorker* worker);

/// Records the recursion of one batch of the request's first pass (its camera rays, or the
/// batch the renderer traces for `batch`, taken across the pass's wavefronts), or, with `crop`,
/// of its rays in `region` of the image (region_pixels()), following one pixel's (first) ray;
/// with `against` (a preset name), the same rays again by EDACRT with that preset, and where
/// the two recursions first decide differently. A batch the request's integrator never traces,
/// or none of whose rays were made, is an error.
std::shared_ptr<const Analysis> analyse(const RenderRequest& request, std::int64_t pixel, bool crop,
                                        ImageRegion region = {}, BatchId batch = {},
                                        const std::string& against = "");

/// "64x64 region at (608, 368)": the recorded crop in words.
std::string region_name(const Analysis& analysis);

/// Runs a change of the camera (OrbitCamera throws InputError for one it refuses): the view
/// is kept and the refusal shown on the status line (the mouse and keys; a script fails).
template <typename Change>
void change_camera(ViewerState& state, Change&& change) {
    try {
        change();
    } catch (const InputError& e) {
        state.status = e.what();
    }
}

/// Orbits about the surface point under fractions (u, v) of the image (the first hit of the
/// camera ray there, from the rendered image's aspect): the eye stays, the look-at point
/// becomes that point. Returns false, the view unchanged and the status line saying why,
/// when the ray hits nothing or the camera refuses the point.
bool orbit_about_pixel(ViewerState& state, float u, float v);

/// Saves the view as the scene's bookmark `name` (replacing one of that name) and writes the
/// bookmarks file, for the Camera tab's "save view" and the script's `bookmark`; the status
/// line says where. Throws InputError ("bookmarks not saved: ...") when no file is known
/// (neither XDG_CONFIG_HOME nor HOME is set) or it cannot be written.
void save_bookmark(ViewerState& state, const std::string& name);

/// Removes the scene's bookmark `name` and writes the file; throws as save_bookmark() does.
void remove_bookmark(ViewerState& state, const std::string& name);

/// Throws InputError when the output `path` (written by `what`: "screenshot", "layout", ...)
/// is a file the viewer reads: the scene's files (OBJ, MTL libraries, animation file, key
/// frames: Scene::inputs), the script being run, or (unless `what` is the bookmarks file
/// itself) the bookmarks file; through links too (check_distinct_files()).
void check_output_spares_inputs(const ViewerState& state, const std::string& path,
                                const std::string& what);

/// SAVE_DIR/SCENE-YYYYmmdd-HHMMSS.EXT.
std::string timestamped(const ViewerState& state, const std::string& extension);

}  // namespace edacrt::app
