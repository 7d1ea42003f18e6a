#include "viewer_jobs.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <future>
#include <iostream>
#include <numeric>

#include "render/benchmark_rays.h"
#include "render/default_camera.h"
#include "render/render_memory.h"
#include "render/wavefront.h"
#include "trace/naive_tracer.h"
#include "util/error.h"
#include "util/output_file.h"
#include "util/printable.h"

namespace edacrt::app {
namespace {

using Clock = std::chrono::steady_clock;

/// The scene `spec` names, animated as `animation` says, and its default view (whose probe
/// rays, for an interior, take a second in a large scene); throws on failure. Runs off the UI
/// thread (poll_loads()).
LoadedScene read_scene(const std::string& spec, const std::string& animation) {
    // An animation file or OBJ sequence names its own geometry.
    const bool own = animation_has_geometry(spec);
    LoadedScene loaded{load_animated_scene(own ? "" : spec, own ? spec : animation), {}};
    if (loaded.animated.scene.triangle_count() == 0)
        throw InputError(spec + ": the scene has no triangles");
    loaded.view = default_camera(loaded.animated.scene);
    return loaded;
}

/// Makes a scene read by read_scene() the state's.
void take_scene(ViewerState& s, LoadedScene loaded, const std::string& spec,
                const CameraOptions& flags, const std::string& animation, bool keep_view) {
    const bool own = animation_has_geometry(spec);
    AnimatedScene& animated = loaded.animated;
    Playback playback;
    std::shared_ptr<const Scene> scene;
    if (animated.animation) {
        playback.frames = std::make_shared<FramePool>(std::move(animated));
        scene = playback.frames->at(0.0);
    } else {
        scene = std::make_shared<const Scene>(std::move(animated.scene));
    }
    if (!s.integrator_chosen) s.ui.integrator = default_integrator(*scene);
    if (!keep_view) {
        s.scene_camera = loaded.view;
        s.camera.reset(flags.given() ? choose_camera(*scene, flags) : loaded.view);
    }
    // The file's name only: an absolute path wraps the tab's header onto several lines (the
    // full path is the header's tooltip).
    s.scene_label = std::filesystem::path(scene->source).filename().string() + ": " +
                    std::to_string(scene->triangle_count()) + " triangles";
    if (playback.frames) s.scene_label += ", animated (" + playback.frames->spec() + ")";
    for (const std::string& w : scene->warnings)
        std::cerr << "edacrt_viewer: warning: " << printable(w) << "\n";
    // Playback settings carry over; the frames, the time and the history start over.
    playback.speed = s.playback.speed;
    playback.play_scale = s.playback.play_scale;
    playback.loop = s.playback.loop;
    playback.motion_blur = s.playback.motion_blur;
    playback.shutter = s.playback.shutter;
    playback.update = s.playback.update;
    playback.playing = playback.frames && s.playback.playing;
    s.playback = std::move(playback);
    s.scene = std::move(scene);
    ++s.scene_number;
    s.scene_error.clear();
    s.scene_path = spec;
    s.animation_spec = own ? "" : animation;
    s.animation_field = s.playback.frames && !own ? s.playback.frames->spec() : "";
}

}  // namespace

/// Loads a scene into the state; on failure keeps the previous one and shows the error. The
/// camera flags override the scene's view (render/camera_options.h), for the first scene only.
void load_into(ViewerState& s, const std::string& spec, const CameraOptions& flags,
               const std::string& animation, bool keep_view) {
    try {
        take_scene(s, read_scene(spec, animation), spec, flags, animation, keep_view);
    } catch (const std::exception& e) {
        s.scene_error = e.what();
    }
}

void poll_loads(ViewerState& s) {
    if (s.loading &&
        s.loading->scene.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        SceneLoad load = std::move(*s.loading);
        s.loading.reset();
        try {
            take_scene(s, load.scene.get(), load.spec, {}, "", false);
        } catch (const std::exception& e) {
            s.scene_error = e.what();
        }
    }
    if (!s.loading && !s.pending_loads.empty()) {
        std::string spec = s.pending_loads.front();
        s.pending_loads.erase(s.pending_loads.begin());
        s.loading = SceneLoad{spec, Clock::now(),
                              std::async(std::launch::async, read_scene, spec, std::string())};
    }
}

/// The request for the current settings; width x height: the image region in framebuffer
/// pixels.
RenderRequest make_request(const ViewerState& s, int width, int height) {
    RenderRequest r;
    r.scene = s.scene;
    r.camera = s.camera.camera();
    r.method = s.ui.method;
    r.params = s.ui.params;
    r.embree_mode = s.ui.embree_mode;
    r.settings.width = std::max(1, int(float(width) * s.ui.resolution_scale));
    r.settings.height = std::max(1, int(float(height) * s.ui.resolution_scale));
    r.settings.integrator = s.ui.integrator;
    r.settings.primary = s.ui.primary;
    r.settings.max_depth = s.ui.max_depth;
    r.settings.ao_samples = s.ui.ao_samples;
    r.settings.seed = std::uint32_t(s.ui.seed);
    // The first pass renders one sample; once the view is still, passes take several samples
    // of every pixel as one wavefront (large batches), in wavefronts small enough that a
    // change cancels within a fraction of a second.
    r.settings.samples_per_pass = 4;
    r.settings.wavefront_paths = std::size_t(1) << 18;
    r.spp_target = s.ui.spp_target;
    r.threads = s.ui.threads;
    if (const Playback& p = s.playback; p.frames) {
        r.animation = p.frames;
        r.time = p.time;
        r.shutter = p.motion_blur ? double(p.shutter) : 0.0;
        r.update = p.update;
        if (p.playing) {  // each frame is shown once its first pass is done: no preview
            r.preview_scale = 1;
            r.settings.width = std::max(1, r.settings.width / p.play_scale);
            r.settings.height = std::max(1, r.settings.height / p.play_scale);
        }
    }
    return r;
}

// Bytes per pixel the viewer holds besides the renderer: up to three published frames (the
// worker's newest, the one shown, the one shown before), the first pass's per-ray statistics
// twice (captured and published), the driver's float texture (RGBA) and the heat map's values
// and texture; plus the statistics batch, all of a pass's camera rays traced at once
// (trace_bytes_per_ray(true): rays, hits, the tracer's buffers, the observer's).
const std::uint64_t kViewerBytesPerPixel = 3 * sizeof(glm::vec3) + 2 * sizeof(RayStats) +
                                           4 * sizeof(float) + 2 * sizeof(float) +
                                           trace_bytes_per_ray(true);

/// A new resolution (slider or window size) is taken only if the render fits in memory.
/// Otherwise the error shows (and is printed once) and the previous resolution stays, the
/// slider included. Returns false when there is no resolution to render at yet.
bool fit_resolution(ViewerState& s, RenderRequest& request, const RenderRequest& submitted) {
    if (request.settings.width == submitted.settings.width &&
        request.settings.height == submitted.settings.height)
        return true;
    try {
        check_render_memory(request.settings, kViewerBytesPerPixel);
        s.resolution_error.clear();
        s.accepted_resolution_scale = s.ui.resolution_scale;
        return true;
    } catch (const InputError& e) {
        if (s.resolution_error != e.what())
            std::cerr << "edacrt_viewer: error: " << printable(e.what()) << "\n";
        s.resolution_error = e.what();
        s.ui.resolution_scale = s.accepted_resolution_scale;
        request.settings.width = submitted.settings.width;
        request.settings.height = submitted.settings.height;
        return submitted.settings.width > 0;
    }
}

namespace {

/// Throws InputError when tracing `rays` rays (with statistics: `detail`) would take more than
/// half the memory limit (the paused render keeps the rest): "N rays WHAT need ...; ADVICE".
void check_trace_memory(std::uint64_t rays, bool detail, const std::string& what,
                        const std::string& advice) {
    const std::uint64_t need = rays * trace_bytes_per_ray(detail);
    const MemoryLimit limit = memory_limit();
    if (need > limit.bytes / 2)
        throw InputError(std::to_string(rays) + " rays " + what + " need about " +
                         std::to_string(need / 1'000'000) + " MB, more than half the " +
                         std::to_string(limit.bytes / 1'000'000) + " MB of " + limit.source + "; " +
                         advice);
}

}  // namespace

std::vector<Ray> compare_rays(const Camera& camera, int width, int height, int spp,
                              std::uint32_t seed) {
    const std::uint64_t rays = std::uint64_t(width) * std::uint64_t(height) * std::uint64_t(spp);
    check_trace_memory(rays, false, "(" + std::to_string(spp) + " per pixel)",
                       "choose fewer rays per pixel");
    const PinholeProjection projection(camera, width, height);
    if (spp == 1) return projection.pixel_centre_rays();
    return jittered_camera_rays(projection, width, height, spp, seed);
}

/// Traces the camera rays with every method (the Statistics tab), once the render has paused
/// (its pass in flight finished): the median of three update + trace, where the update is
/// set_scene() (per-frame cost: nothing is kept between frames) or, for a frame of an
/// animation, also a refit or dynamic commit from the previous frame (untimed).
std::vector<MethodTotals> compare_methods(std::shared_ptr<const Scene> scene,
                                          std::shared_ptr<const Scene> previous, Camera camera,
                                          int width, int height, int spp, std::uint32_t seed,
                                          EdacrtParams params, const RenderWorker* worker) {
    worker->wait_idle(std::chrono::seconds(60));
    std::vector<Ray> rays;
    std::string rays_error;  // every method's row shows it
    try {
        rays = compare_rays(camera, width, height, spp, seed);
    } catch (const InputError& e) {
        rays_error = e.what();
    }
    std::vector<Hit> hits(rays.size());
    std::vector<std::pair<Method, SceneUpdate>> variants;
    for (Method method : {Method::edacrt, Method::dacrt, Method::bvh, Method::embree}) {
        variants.emplace_back(method, SceneUpdate::rebuild);
        if (previous && method == Method::bvh) variants.emplace_back(method, SceneUpdate::refit);
        if (previous && method == Method::embree)
            for (SceneUpdate how : {SceneUpdate::dynamic, SceneUpdate::refit})
                variants.emplace_back(method, how);
    }
    variants.emplace_back(Method::naive, SceneUpdate::rebuild);
    std::vector<MethodTotals> out;
    for (const auto& [method, how] : variants) {
        MethodTotals totals;
        totals.method = method;
        totals.update = how;
        totals.spp = spp;
        try {
            if (!rays_error.empty()) throw InputError(rays_error);
            if (method == Method::naive &&
                double(rays.size()) * double(scene->triangle_count()) > 1e9)
                throw InputError("skipped: too slow here");
            double times[3], updates[3];
            for (int run = 0; run < 3; ++run) {
                const auto tracer = make_tracer(method, params);
                if (how != SceneUpdate::rebuild) tracer->update_scene(*previous, how);
                const auto start = Clock::now();
                updates[run] = tracer->update_scene(*scene, how).seconds;
                totals.stats = tracer->trace(rays, hits, Query::closest);
                times[run] = std::chrono::duration<double>(Clock::now() - start).count();
            }
            std::sort(std::begin(times), std::end(times));
            std::sort(std::begin(updates), std::end(updates));
            totals.seconds = times[1];
            totals.update_seconds = updates[1];
        } catch (const std::exception& e) {
            totals.error = e.what();
        }
        out.push_back(totals);
    }
    return out;
}

std::string region_name(const Analysis& a) {
    return std::to_string(a.crop_w) + "x" + std::to_string(a.crop_h) + " region at (" +
           std::to_string(a.crop_x) + ", " + std::to_string(a.crop_y) + ")";
}

/// Records the recursion of one batch of the first pass of the render in progress (the camera
/// rays, which the statistics and heat maps show, or another batch), or of its rays in a region
/// of the image (a small batch to step through), following one pixel.
std::shared_ptr<const Analysis> analyse(const RenderRequest& request, std::int64_t pixel, bool crop,
                                        ImageRegion region, BatchId batch,
                                        const std::string& against) {
    auto a = std::make_shared<Analysis>();
    a->scene = request.scene;
    a->camera = request.camera;
    a->width = request.settings.width;
    a->height = request.settings.height;
    a->seed = request.settings.seed;
    a->method = request.method;
    a->params = request.params;
    a->batch = batch;
    a->settings = request.settings;
    a->pixel = pixel;
    if (crop) {
        const std::array<int, 4> box = region_pixels(region, a->width, a->height);
        a->crop_x = box[0], a->crop_y = box[1], a->crop_w = box[2], a->crop_h = box[3];
    } else {
        a->crop_w = a->width, a->crop_h = a->height;
    }
    try {
        const auto tracer = make_tracer(request.method, request.params, request.embree_mode);
        tracer->set_scene(*request.scene);
        CapturedBatch captured;
        if (batch == BatchId{}) {
            captured.rays = first_pass_camera_rays(request.camera, request.settings);
            captured.pixels.resize(captured.rays.size());
            std::iota(captured.pixels.begin(), captured.pixels.end(), 0u);
        } else {
            captured =
                capture_batch(*request.scene, *tracer, request.camera, request.settings, batch);
            if (captured.rays.empty())
                throw InputError("the first pass made no " + batch_name(batch) +
                                 " rays: every path ended before");
        }
        // The crop's rays, in the batch's order.
        std::vector<Ray> rays;
        for (std::size_t i = 0; i < captured.rays.size(); ++i) {
            const std::uint32_t p = captured.pixels[i];
            const int x = int(p % std::uint32_t(a->width)), y = int(p / std::uint32_t(a->width));
            if (x < a->crop_x || y < a->crop_y || x >= a->crop_x + a->crop_w ||
                y >= a->crop_y + a->crop_h)
                continue;
            rays.push_back(captured.rays[i]);
            a->pixels.push_back(p);
        }
        captured = {};
        if (rays.empty())
            throw InputError("no " + batch_name(batch) + " rays in the " + region_name(*a));
        check_trace_memory(rays.size(), true, "of batch " + batch_name(batch),
                           "lower the resolution or record a region");
        const auto followed = std::find(a->pixels.begin(), a->pixels.end(), std::uint32_t(pixel));
        const std::int64_t follow =
            pixel >= 0 && followed != a->pixels.end() ? followed - a->pixels.begin() : -1;
        std::vector<Hit> hits(rays.size());
        auto detail = std::make_shared<TraceDetail>();
        detail->max_nodes = 300'000;
        detail->max_node_ray_ids = std::size_t(1) << 24;  // 64 MB
        detail->follow_ray = follow;
        tracer->trace(rays, hits, batch_query(batch), detail.get());
        if (follow >= 0) {
            a->hit = hits[std::size_t(follow)];
            a->ray = rays[std::size_t(follow)];
            a->followed = true;
        }
        a->pixel_stats = per_pixel_stats(detail->rays, a->pixels, a->width, a->height);
        if (!against.empty() && !detail->nodes.empty()) {
            const auto other = make_tracer(Method::edacrt, preset_params(against));
            other->set_scene(*request.scene);
            auto b = std::make_shared<TraceDetail>();
            b->max_nodes = detail->max_nodes;
            std::vector<Hit> other_hits(rays.size());
            other->trace(rays, other_hits, batch_query(batch), b.get());
            a->against = against;
            a->against_pixel_stats = per_pixel_stats(b->rays, a->pixels, a->width, a->height);
            a->differences = first_differences(*detail, *b);
            a->against_detail = std::move(b);
        }
        a->detail = std::move(detail);
    } catch (const std::exception& e) {
        a->error = e.what();
    }
    return a;
}

void check_output_spares_inputs(const ViewerState& s, const std::string& path,
                                const std::string& what) {
    std::vector<NamedPath> inputs;
    if (s.scene)
        for (const std::string& file : s.scene->inputs) inputs.push_back({"scene's", file});
    inputs.push_back({"script", s.script_path});
    if (what != "bookmarks") inputs.push_back({"bookmarks", s.bookmarks_path});
    check_distinct_files({{what, path}}, inputs);
}

namespace {

/// Writes the bookmarks file; the status line says where.
void write_bookmarks(ViewerState& s) {
    if (s.bookmarks_path.empty())
        throw InputError("bookmarks not saved: neither XDG_CONFIG_HOME nor HOME is set");
    std::string backup;
    try {
        check_output_spares_inputs(s, s.bookmarks_path, "bookmarks");
        backup = s.bookmarks.save(s.bookmarks_path);
    } catch (const InputError& e) {
        throw InputError(std::string("bookmarks not saved: ") + e.what());
    }
    s.status = "bookmarks saved to " + s.bookmarks_path;
    if (!backup.empty()) {
        s.status += "; the damaged file before it is kept as " + backup;
        std::cerr << "edacrt_viewer: " << printable(s.status) << "\n";
    }
}

}  // namespace

bool orbit_about_pixel(ViewerState& s, float u, float v) {
    if (!s.scene) return false;
    // The image's aspect: of the render, else of the region it will fill.
    const RenderSettings& rendered = s.submitted.settings;
    const bool known = rendered.width > 0 && rendered.height > 0;
    const int width = known ? rendered.width : std::max(1, int(s.layout.image.w));
    const int height = known ? rendered.height : std::max(1, int(s.layout.image.h));
    const Ray ray = PinholeProjection(s.camera.camera(), width, height)
                        .ray(std::clamp(u, 0.0f, 1.0f) * float(width),
                             std::clamp(v, 0.0f, 1.0f) * float(height));
    NaiveTracer tracer;  // one ray: no structure worth building
    tracer.set_scene(*s.scene);
    Hit hit;
    tracer.trace({&ray, 1}, {&hit, 1}, Query::closest);
    if (!hit.hit()) {
        s.status = "nothing under the cursor to orbit about";
        return false;
    }
    const glm::vec3 point = ray.org + hit.t * ray.dir;
    try {
        s.camera.orbit_about(point);
    } catch (const InputError& e) {
        s.status = e.what();
        return false;
    }
    char where[96];
    std::snprintf(where, sizeof where, "orbiting about %g %g %g", point.x, point.y, point.z);
    s.status = where;
    return true;
}

void save_bookmark(ViewerState& s, const std::string& name) {
    s.bookmarks.put(s.scene_path, {name, s.camera.camera()});
    write_bookmarks(s);
}

void remove_bookmark(ViewerState& s, const std::string& name) {
    s.bookmarks.remove(s.scene_path, name);
    write_bookmarks(s);
}

/// A file name from the scene and the time: out/sponza-20261201-235959.png.
std::string timestamped(const ViewerState& s, const std::string& extension) {
    const std::time_t now = std::time(nullptr);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
    std::string stem = std::filesystem::path(s.scene_path).stem().string();
    if (stem.empty() || s.scene_path.rfind("builtin:", 0) == 0)
        stem = s.scene_path.substr(0, s.scene_path.find(':', 8));
    std::replace_if(
        stem.begin(), stem.end(), [](char c) { return !std::isalnum(c) && c != '-'; }, '_');
    return (std::filesystem::path(s.save_dir.empty() ? "." : s.save_dir) /
            (stem + "-" + stamp + extension))
        .string();
}

}  // namespace edacrt::app
