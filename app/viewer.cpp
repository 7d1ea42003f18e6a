#include "viewer.h"

// glad before GLFW, so GLFW does not pull in the system GL header.
#include <glad/gl.h>
// clang-format off
#include <GLFW/glfw3.h>
// clang-format on
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <optional>
#include <tuple>

#include "camera_options.h"
#include "command_line.h"
#include "display.h"
#include "panels/panels.h"
#include "render/default_camera.h"
#include "render/film.h"
#include "render/image.h"
#include "render/render_memory.h"
#include "render/wavefront.h"
#include "script.h"
#include "util/error.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

using Clock = std::chrono::steady_clock;

/// Loads a scene into the state; on failure keeps the previous one and shows the error. The
/// camera flags override the scene's view (cli/camera_options.h), for the first scene only.
void load_into(ViewerState& s, const std::string& spec,
               const cli::CameraOptions& flags = cli::CameraOptions{}) {
    try {
        auto scene = std::make_shared<Scene>(load_scene(spec));
        if (scene->triangle_count() == 0) throw InputError(spec + ": the scene has no triangles");
        s.scene_camera = default_camera(*scene);
        s.camera.reset(cli::choose_camera(*scene, flags));
        s.scene_label =
            scene->source + ": " + std::to_string(scene->triangle_count()) + " triangles";
        for (const std::string& w : scene->warnings)
            std::cerr << "edacrt_viewer: warning: " << w << "\n";
        s.scene = std::move(scene);
        s.scene_error.clear();
        s.scene_path = spec;
    } catch (const std::exception& e) {
        s.scene_error = e.what();
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
            std::cerr << "edacrt_viewer: error: " << e.what() << "\n";
        s.resolution_error = e.what();
        s.ui.resolution_scale = s.accepted_resolution_scale;
        request.settings.width = submitted.settings.width;
        request.settings.height = submitted.settings.height;
        return submitted.settings.width > 0;
    }
}

/// Traces one camera ray per pixel with every method (the Statistics tab), once the render
/// has paused (its pass in flight finished): the median of three traces after the tracer's
/// set_scene, which the median includes (per-frame cost: nothing is kept between frames).
std::vector<MethodTotals> compare_methods(std::shared_ptr<const Scene> scene, Camera camera,
                                          int width, int height, EdacrtParams params,
                                          const RenderWorker* worker) {
    worker->wait_idle(std::chrono::seconds(60));
    const std::vector<Ray> rays = PinholeProjection(camera, width, height).pixel_centre_rays();
    std::vector<Hit> hits(rays.size());
    std::vector<MethodTotals> out;
    for (Method method :
         {Method::edacrt, Method::dacrt, Method::bvh, Method::embree, Method::naive}) {
        MethodTotals totals;
        totals.method = method;
        try {
            if (method == Method::naive &&
                double(rays.size()) * double(scene->triangle_count()) > 5e9)
                throw InputError("skipped: too slow here");
            double times[3];
            for (double& t : times) {
                const auto start = Clock::now();
                const auto tracer = make_tracer(method, params);
                tracer->set_scene(*scene);
                totals.stats = tracer->trace(rays, hits, Query::closest);
                t = std::chrono::duration<double>(Clock::now() - start).count();
            }
            std::sort(std::begin(times), std::end(times));
            totals.seconds = times[1];
        } catch (const std::exception& e) {
            totals.error = e.what();
        }
        out.push_back(totals);
    }
    return out;
}

/// Records the recursion of the first pass's camera rays of the render in progress (the batch
/// the statistics and heat maps show), or of a 64x64 crop of them at the image centre (a
/// small batch to step through), following one pixel.
std::shared_ptr<const Analysis> analyse(const RenderRequest& request, std::int64_t pixel,
                                        bool crop) {
    auto a = std::make_shared<Analysis>();
    a->scene = request.scene;
    a->camera = request.camera;
    a->width = request.settings.width;
    a->height = request.settings.height;
    a->seed = request.settings.seed;
    a->method = request.method;
    a->params = request.params;
    a->pixel = pixel;
    a->crop_w = crop ? std::min(64, a->width) : a->width;
    a->crop_h = crop ? std::min(64, a->height) : a->height;
    a->crop_x = (a->width - a->crop_w) / 2;
    a->crop_y = (a->height - a->crop_h) / 2;
    try {
        std::vector<Ray> rays = first_pass_camera_rays(request.camera, request.settings);
        std::int64_t follow = -1;
        if (crop) {
            std::vector<Ray> batch;
            for (int y = 0; y < a->crop_h; ++y)
                for (int x = 0; x < a->crop_w; ++x) {
                    const std::int64_t p = std::int64_t(a->crop_y + y) * a->width + (a->crop_x + x);
                    if (p == pixel) follow = std::int64_t(batch.size());
                    batch.push_back(rays[std::size_t(p)]);
                }
            rays = std::move(batch);
        } else {
            follow = pixel;
        }
        std::vector<Hit> hits(rays.size());
        auto detail = std::make_shared<TraceDetail>();
        detail->max_nodes = 300'000;
        detail->max_node_ray_ids = std::size_t(1) << 24;  // 64 MB
        detail->follow_ray = follow;
        const auto tracer = make_tracer(request.method, request.params, request.embree_mode);
        tracer->set_scene(*request.scene);
        tracer->trace(rays, hits, Query::closest, detail.get());
        if (follow >= 0) {
            a->hit = hits[std::size_t(follow)];
            a->ray = rays[std::size_t(follow)];
        }
        a->detail = std::move(detail);
    } catch (const std::exception& e) {
        a->error = e.what();
    }
    return a;
}

/// Saves a region of the back buffer (what the window shows; x, y from the top-left, in
/// framebuffer pixels) as PNG, creating the folder.
void save_framebuffer(const std::string& path, int x, int y, int width, int height,
                      int framebuffer_height) {
    const std::size_t row = std::size_t(width) * 3;
    std::vector<std::uint8_t> pixels(row * std::size_t(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(x, framebuffer_height - y - height, width, height, GL_RGB, GL_UNSIGNED_BYTE,
                 pixels.data());
    // OpenGL rows start at the bottom.
    for (std::size_t top = 0, bottom = std::size_t(height) - 1; top < bottom; ++top, --bottom)
        std::swap_ranges(pixels.begin() + std::ptrdiff_t(top * row),
                         pixels.begin() + std::ptrdiff_t((top + 1) * row),
                         pixels.begin() + std::ptrdiff_t(bottom * row));
    const std::filesystem::path out(path);
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    write_png_rgb8(out, pixels, width, height);
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

/// Runs the script one step per frame; false when it has ended (or failed: `error` is set).
class ScriptRunner {
  public:
    explicit ScriptRunner(std::vector<ScriptCommand> commands) : commands_(std::move(commands)) {}

    bool active() const { return next_ < commands_.size(); }

    /// `shown_spp`: samples of the current request on screen (0 while a preview is shown).
    void step(ViewerState& s, int shown_spp, std::string& screenshot, bool& quit) {
        while (next_ < commands_.size()) {
            const ScriptCommand& c = commands_[next_];
            const auto fail = [&](const std::string& what) {
                throw InputError("script line " + std::to_string(c.line) + ": " + what);
            };
            const auto choice = [&](const char* yes, const char* no) {
                if (c.args[0] != yes && c.args[0] != no)
                    fail("'" + c.verb + "' takes " + yes + " or " + no);
                return c.args[0] == yes;
            };
            if (c.verb == "wait-spp") {
                if (!waiting_) wait_start_ = Clock::now();
                waiting_ = true;
                if (shown_spp < std::stoi(c.args[0])) {
                    if (Clock::now() - wait_start_ > std::chrono::minutes(5))
                        fail("timed out waiting for " + c.args[0] + " spp");
                    return;
                }
                waiting_ = false;
            } else if (c.verb == "frames") {
                if (frames_left_ < 0) frames_left_ = std::stoi(c.args[0]);
                if (frames_left_-- > 0) return;
                frames_left_ = -1;
            } else if (c.verb == "set" || c.verb == "orbit") {
                if (c.verb == "set")
                    apply_setting(s, c.args[0], c.args[1]);
                else
                    s.camera.orbit(std::stof(c.args[0]), std::stof(c.args[1]));
                ++next_;
                return;  // the next frame submits the change before anything waits on it
            } else if (c.verb == "view") {
                s.view = parse_view(c.args[0]);
            } else if (c.verb == "tab") {
                std::string name = c.args[0];
                std::replace(name.begin(), name.end(), '_', ' ');
                s.select_tabs.push_back(name);
            } else if (c.verb == "panels") {
                s.panels_hidden = choice("hidden", "shown");
            } else if (c.verb == "analysis") {
                s.analysis_open = choice("open", "closed");
            } else if (c.verb == "help") {
                s.show_help = choice("on", "off");
            } else if (c.verb == "check-layout") {
                std::string report;
                for (const std::string& p : s.layout_problems) report += "\n  " + p;
                if (!report.empty()) fail("layout problems:" + report);
                std::cout << "layout ok: " << s.placements.size() << " panels, image "
                          << s.layout.image.x << " " << s.layout.image.y << " " << s.layout.image.w
                          << " " << s.layout.image.h << "\n";
            } else if (c.verb == "save-view" || c.verb == "save-linear") {
                s.save_path = c.args[0];
                s.save_requested =
                    c.verb == "save-view" ? ViewerState::Save::shown : ViewerState::Save::linear;
                ++next_;
                return;  // saved in the next frame, one file per frame
            } else if (c.verb == "write-command") {
                std::ofstream out(c.args[0]);
                out << s.command_line << "\n";
                if (!out) fail("cannot write " + c.args[0]);
            } else if (c.verb == "record") {
                s.analysis_requested = true;
                analysis_asked_ = true;
            } else if (c.verb == "pick") {
                pick_ = ImVec2(std::stof(c.args[0]), std::stof(c.args[1]));
                analysis_asked_ = true;
            } else if (c.verb == "wait-analysis") {
                if (analysis_asked_ || s.analysis_running || s.analysis_requested) {
                    analysis_asked_ = s.analysis_running || s.analysis_requested;
                    return;
                }
            } else if (c.verb == "screenshot") {
                screenshot = c.args[0];
                ++next_;
                return;  // taken at the end of this frame
            } else if (c.verb == "quit") {
                quit = true;
            }
            ++next_;
        }
    }

    /// A window position to pick (the traversal debugger), consumed by the viewer.
    std::optional<ImVec2> take_pick() { return std::exchange(pick_, std::nullopt); }

  private:
    std::vector<ScriptCommand> commands_;
    std::optional<ImVec2> pick_;
    bool analysis_asked_ = false;
    std::size_t next_ = 0;
    int frames_left_ = -1;
    bool waiting_ = false;
    Clock::time_point wait_start_;
};

/// Keys (while no text field has the keyboard): Tab or F1 hide the panels, H or ? the help,
/// F12 saves the image, Esc quits, R resets the view, WASD/QE fly. ImGui 1.86 indexes keys
/// by the backend's (GLFW's) key codes.
void handle_keys(ViewerState& s, float dt, bool& quit) {
    const ImGuiIO& io = ImGui::GetIO();
    if (io.WantTextInput) return;
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) quit = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_F12, false)) s.save_requested = ViewerState::Save::shown;
    if (io.WantCaptureKeyboard) return;
    if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false) || ImGui::IsKeyPressed(GLFW_KEY_F1, false))
        s.panels_hidden = !s.panels_hidden;
    if (ImGui::IsKeyPressed(GLFW_KEY_H, false) ||
        (ImGui::IsKeyPressed(GLFW_KEY_SLASH, false) && io.KeyShift))
        s.show_help = !s.show_help;
    const auto key = [&](int k) { return ImGui::IsKeyDown(k) ? 1.0f : 0.0f; };
    const float forward = key(GLFW_KEY_W) - key(GLFW_KEY_S);
    const float right = key(GLFW_KEY_D) - key(GLFW_KEY_A);
    const float up = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
    if (forward != 0 || right != 0 || up != 0) s.camera.fly(forward, right, up, dt);
    if (ImGui::IsKeyPressed(GLFW_KEY_R)) s.camera.reset(s.scene_camera);
}

/// The region in framebuffer pixels: x, y from the top-left, width, height.
struct PixelRect {
    int x = 0, y = 0, w = 0, h = 0;
};
PixelRect to_pixels(const Rect& r, float scale_x, float scale_y) {
    const int x0 = int(std::lround(r.x * scale_x)), y0 = int(std::lround(r.y * scale_y));
    const int x1 = int(std::lround(r.right() * scale_x)),
              y1 = int(std::lround(r.bottom() * scale_y));
    return {x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
    ViewerState s;
    std::optional<ScriptRunner> script;
    try {
        s.ui.method = parse_method(options.method);
        s.ui.integrator = parse_integrator(options.integrator);
        s.ui.spp_target = options.spp;
        if (!options.script.empty()) script.emplace(load_script(options.script));
    } catch (const std::exception& e) {
        std::cerr << "edacrt_viewer: error: " << e.what() << "\n";
        return 1;
    }
    s.panels_hidden = options.hide_panels;
    load_into(s, options.scene, options.camera);
    if (!s.scene) {
        std::cerr << "edacrt_viewer: error: " << s.scene_error << "\n";
        return 1;
    }
    s.bookmarks_path = options.bookmarks.empty() ? Bookmarks::default_path() : options.bookmarks;
    try {
        if (!s.bookmarks_path.empty()) s.bookmarks.load(s.bookmarks_path);
    } catch (const std::exception& e) {
        std::cerr << "edacrt_viewer: warning: " << e.what() << " (bookmarks start empty)\n";
    }
    const std::filesystem::path assets = options.assets_dir.empty()
                                             ? std::filesystem::path("assets")
                                             : std::filesystem::path(options.assets_dir);
    s.scene_list = scene_catalog(assets);

    glfwSetErrorCallback([](int code, const char* text) {
        std::cerr << "edacrt_viewer: GLFW error " << code << ": " << text << "\n";
    });
    if (!glfwInit()) {
        std::cerr << "edacrt_viewer: error: cannot initialise GLFW (is there a display?)\n";
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow* window =
        glfwCreateWindow(options.width, options.height, "EDACRT Studio", nullptr, nullptr);
    if (!window) {
        std::cerr << "edacrt_viewer: error: cannot open an OpenGL 3.3 core window\n";
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
    if (!gladLoadGL(glfwGetProcAddress)) {
        std::cerr << "edacrt_viewer: error: cannot load OpenGL 3.3 functions\n";
        glfwTerminate();
        return 1;
    }
    glfwSetWindowUserPointer(window, &s);
    glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
        auto* state = static_cast<ViewerState*>(glfwGetWindowUserPointer(w));
        for (int i = 0; i < count; ++i) state->pending_loads.emplace_back(paths[i]);
    });

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the same layout every start (and in tests)
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330");

    int exit_code = 0;
    {
        Display display;
        RenderWorker worker;
        RenderRequest& submitted = s.submitted;
        std::uint64_t request_id = 0;
        std::shared_ptr<const Frame> uploaded, shown_last_frame;
        View uploaded_view = View::render;
        float heat_max = 1.0f;
        std::tuple<const Analysis*, std::int32_t, int> tint_key{nullptr, -1, -1};
        std::future<std::vector<MethodTotals>> comparison;
        std::future<std::shared_ptr<const Analysis>> analysis;
        auto last = Clock::now();
        const auto first = last;
        float slowest_frame = 0.0f;  // seconds, after the first few frames (start-up)
        int frame_number = 0;
        bool quit = false;
        while (!glfwWindowShouldClose(window) && !quit) {
            glfwPollEvents();
            const auto now = Clock::now();
            const float dt = std::chrono::duration<float>(now - last).count();
            last = now;
            if (frame_number > 5) slowest_frame = std::max(slowest_frame, dt);

            for (const std::string& spec : std::exchange(s.pending_loads, {})) load_into(s, spec);

            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            const ImGuiIO& io = ImGui::GetIO();
            s.layout = compute_layout({io.DisplaySize.x, io.DisplaySize.y, ImGui::GetFontSize(),
                                       ImGui::GetFrameHeight(), s.panels_hidden, s.analysis_open});
            const Rect& image = s.layout.image;
            const auto in_image = [&](ImVec2 p) {
                return p.x >= image.x && p.y >= image.y && p.x < image.right() &&
                       p.y < image.bottom();
            };
            // The traversal debugger's pixel: a click on the image while picking, or the script.
            std::optional<ImVec2> pick = script ? script->take_pick() : std::nullopt;
            if (s.picking && !io.WantCaptureMouse && in_image(io.MousePos) &&
                ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
                pick = io.MousePos;
                s.picking = false;
            }
            if (pick && submitted.settings.width > 0 && in_image(*pick)) {
                const int x =
                    std::clamp(int((pick->x - image.x) / image.w * float(submitted.settings.width)),
                               0, submitted.settings.width - 1);
                const int y = std::clamp(
                    int((pick->y - image.y) / image.h * float(submitted.settings.height)), 0,
                    submitted.settings.height - 1);
                s.follow_pixel = std::int64_t(y) * submitted.settings.width + x;
                s.analysis_requested = true;
            } else if (!io.WantCaptureMouse) {
                // Drags that start on the image move the camera.
                const ImVec2 d = io.MouseDelta;
                const auto drag = [&](ImGuiMouseButton b) {
                    return ImGui::IsMouseDragging(b) && in_image(io.MouseClickedPos[b]);
                };
                if (drag(ImGuiMouseButton_Left)) s.camera.orbit(d.x, d.y);
                if (drag(ImGuiMouseButton_Right) || drag(ImGuiMouseButton_Middle))
                    s.camera.pan(d.x, d.y, image.h);
                if (io.MouseWheel != 0.0f && in_image(io.MousePos)) s.camera.zoom(io.MouseWheel);
            }
            handle_keys(s, dt, quit);

            if (auto frame = worker.latest(); frame && frame->request == request_id) {
                s.render_error = frame->error;
                if (frame->error.empty() && frame != s.frame) {
                    if (frame->preview) s.convergence.clear();
                    if (!frame->preview && s.frame && !s.frame->preview &&
                        s.frame->request == frame->request && s.frame->spp < frame->spp)
                        s.convergence.push_back(
                            {frame->seconds, frame->spp,
                             relative_rms_change(frame->image, s.frame->image)});
                    s.frame = frame;
                }
            }
            s.analysis_stale = s.analysis && analysis_stale(*s.analysis, submitted);
            s.placements.clear();
            s.recursion_shown = false;
            draw_controls(s);
            draw_analysis(s, heat_max);
            draw_help(s);
            draw_heat_readout(s);

            // A changed setting, camera, scene or image region starts a new render.
            int fb_width = 0, fb_height = 0;
            glfwGetFramebufferSize(window, &fb_width, &fb_height);
            const float scale_x = io.DisplaySize.x > 0 ? float(fb_width) / io.DisplaySize.x : 1.0f;
            const float scale_y = io.DisplaySize.y > 0 ? float(fb_height) / io.DisplaySize.y : 1.0f;
            const PixelRect region = to_pixels(image, scale_x, scale_y);
            if (region.w > 0 && region.h > 0) {
                RenderRequest request = make_request(s, region.w, region.h);
                const bool changed = fit_resolution(s, request, submitted) &&
                                     (request_id == 0 || request != submitted);
                if (changed) {
                    // A new request restarts the film (pausing does not: see below).
                    submitted = request;
                    request_id = worker.submit(std::move(request));
                }
            }
            s.command_line = render_command_line(
                {s.scene_path, submitted.method, submitted.embree_mode, submitted.params,
                 submitted.settings, submitted.camera, submitted.spp_target, s.exposure,
                 std::array{"clamp", "reinhard", "aces"}[std::size_t(s.tone_map)],
                 timestamped(s, ".png")});

            // The render pauses while methods are compared: their timings get the cores.
            s.comparing = comparison.valid();
            worker.set_paused(s.ui.paused || s.comparing);
            // Show the newest pass (of the request in force); upload only when it is new.
            if (s.frame && (s.frame != uploaded || s.view != uploaded_view)) {
                if (s.frame != uploaded) display.upload_render(s.frame->image);
                if (s.view != View::render && s.frame->detail) {
                    const std::vector<float> values = heat_values(*s.frame->detail, s.view);
                    heat_max = std::max(1.0f, *std::max_element(values.begin(), values.end()));
                    display.upload_heat(values, s.frame->image.width, s.frame->image.height);
                }
                uploaded = s.frame;
                uploaded_view = s.view;
            }

            if (s.analysis_requested && !analysis.valid() && s.scene &&
                submitted.settings.width > 0) {
                s.analysis_requested = false;
                s.analysis_running = true;
                analysis = std::async(std::launch::async, analyse, submitted, s.follow_pixel,
                                      s.explorer_crop);
            }
            if (analysis.valid() &&
                analysis.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
                s.analysis = analysis.get();
                s.analysis_running = false;
            }
            if (s.compare_requested && !comparison.valid()) {
                s.compare_requested = false;
                worker.set_paused(true);
                comparison = std::async(std::launch::async, compare_methods, s.scene,
                                        submitted.camera, submitted.settings.width,
                                        submitted.settings.height, s.ui.params, &worker);
            }
            if (comparison.valid() &&
                comparison.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
                s.comparison = comparison.get();

            // The explorer's tint: the selected node's pixels, and in step-through the hits
            // found so far; uploaded when any of them changes.
            const bool tint = s.recursion_shown && s.explorer_tint && s.analysis &&
                              !s.analysis_stale && s.analysis->detail &&
                              !s.analysis->detail->nodes.empty();
            if (tint) {
                const auto key =
                    std::tuple(s.analysis.get(), s.explorer_node, s.stepping ? s.step : -1);
                if (key != tint_key) {
                    display.upload_tint(
                        explorer_tint(*s.analysis, s.explorer_node, s.stepping ? s.step : -1),
                        s.analysis->width, s.analysis->height);
                    tint_key = key;
                }
            }
            const bool heat =
                s.view != View::render && s.frame && s.frame->detail && uploaded_view == s.view;
            ImGui::Render();
            glViewport(0, 0, fb_width, fb_height);
            glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            // The image fills its region (the render has the region's aspect).
            glViewport(region.x, fb_height - region.y - region.h, region.w, region.h);
            if (s.frame) display.draw(heat, {s.exposure, s.tone_map}, heat_max, s.heat_log);
            if (tint) display.draw_tint();
            glViewport(0, 0, fb_width, fb_height);

            // Saving: the image region as shown (overlays are drawn with the UI), or the
            // linear render.
            const auto save_shown = [&] {
                const std::string path = s.save_path.empty() ? timestamped(s, ".png") : s.save_path;
                save_framebuffer(path, region.x, region.y, region.w, region.h, fb_height);
                s.status = "saved " + path;
                std::cout << "saved " << path << "\n";
            };
            const auto save = std::exchange(s.save_requested, ViewerState::Save::none);
            try {
                if (save == ViewerState::Save::shown && !s.save_overlays) save_shown();
                if (save == ViewerState::Save::linear && s.frame) {
                    const std::string path =
                        s.save_path.empty() ? timestamped(s, ".pfm") : s.save_path;
                    const std::filesystem::path out(path);
                    if (out.has_parent_path())
                        std::filesystem::create_directories(out.parent_path());
                    write_pfm(path, s.frame->image);
                    s.status = "saved " + path;
                    std::cout << "saved " << path << "\n";
                }
            } catch (const std::exception& e) {
                s.status = e.what();
                std::cerr << "edacrt_viewer: error: " << e.what() << "\n";
            }
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            try {
                if (save == ViewerState::Save::shown && s.save_overlays) save_shown();
            } catch (const std::exception& e) {
                s.status = e.what();
                std::cerr << "edacrt_viewer: error: " << e.what() << "\n";
            }
            if (save != ViewerState::Save::none) s.save_path.clear();
            s.layout_problems =
                layout_problems(s.layout, io.DisplaySize.x, io.DisplaySize.y, s.placements);

            ++frame_number;
            std::string screenshot;
            // A pass counts as shown once it has been on screen for a whole frame: ImGui sizes
            // new table columns from the previous frame's contents.
            const bool settled = s.frame && s.frame == shown_last_frame;
            shown_last_frame = s.frame;
            const int shown_spp =
                settled && s.frame->request == request_id && !s.frame->preview ? s.frame->spp : 0;
            try {
                if (script) {
                    script->step(s, shown_spp, screenshot, quit);
                    if (!script->active() && options.frames == 0) quit = true;
                }
                // --frames: at the last frame, once a full-resolution pass is on screen.
                if (options.frames > 0 && frame_number >= options.frames && shown_spp > 0 &&
                    (!script || !script->active())) {
                    if (!options.screenshot.empty()) screenshot = options.screenshot;
                    quit = true;
                }
                if (!screenshot.empty()) {
                    save_framebuffer(screenshot, 0, 0, fb_width, fb_height, fb_height);
                    std::cout << "screenshot " << screenshot << " (" << fb_width << "x" << fb_height
                              << ", " << shown_spp << " spp, frame " << frame_number
                              << ", image region " << region.x << " " << region.y << " " << region.w
                              << " " << region.h << ")\n";
                }
            } catch (const std::exception& e) {
                std::cerr << "edacrt_viewer: error: " << e.what() << "\n";
                exit_code = 1;
                quit = true;
            }
            glfwSwapBuffers(window);
        }
        if (comparison.valid()) comparison.wait();
        if (analysis.valid()) analysis.wait();
        if (options.frames > 0 || script) {  // headless runs report the UI's frame rate
            const double seconds = std::chrono::duration<double>(Clock::now() - first).count();
            std::cout << frame_number << " frames in " << seconds << " s ("
                      << double(frame_number) / seconds << " fps), slowest frame "
                      << slowest_frame * 1e3f << " ms\n";
        }
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return exit_code;
}

}  // namespace edacrt::app
