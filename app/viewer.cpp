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
#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <iostream>
#include <optional>

#include "display.h"
#include "render/film.h"
#include "render/image.h"
#include "render/image_format.h"
#include "render/render_memory.h"
#include "render/render_metadata.h"
#include "script.h"
#include "util/error.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

using Clock = std::chrono::steady_clock;

/// The scenes offered in the list: the bundled OBJ files and the built-in scenes.
std::vector<std::string> scene_list(const std::filesystem::path& assets) {
    std::vector<std::string> list;
    std::error_code error;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(assets, error))
        if (entry.path().extension() == ".obj") list.push_back(entry.path().string());
    std::sort(list.begin(), list.end());
    for (const char* builtin : {"builtin:cornell", "builtin:sphere:subdiv=5", "builtin:cube:n=8"})
        list.emplace_back(builtin);
    return list;
}

/// Loads a scene into the state; on failure keeps the previous one and shows the error.
void load_into(ViewerState& s, const std::string& spec) {
    try {
        auto scene = std::make_shared<Scene>(load_scene(spec));
        if (scene->triangle_count() == 0) throw InputError(spec + ": the scene has no triangles");
        s.scene_camera = scene->camera.value_or(frame_box(scene->bounds()));
        s.camera.reset(s.scene_camera);
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

/// Traces one camera ray per pixel with every method (for the statistics panel).
std::vector<MethodTotals> compare_methods(std::shared_ptr<const Scene> scene, Camera camera,
                                          int width, int height, EdacrtParams params) {
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
            const auto tracer = make_tracer(method, params);
            tracer->set_scene(*scene);
            const auto start = Clock::now();
            totals.stats = tracer->trace(rays, hits, Query::closest);
            totals.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        } catch (const std::exception& e) {
            totals.error = e.what();
        }
        out.push_back(totals);
    }
    return out;
}

/// Records the recursion of the view's pixel-centre camera rays, following one pixel.
std::shared_ptr<const Analysis> analyse(std::shared_ptr<const Scene> scene, Camera camera,
                                        int width, int height, Method method, EdacrtParams params,
                                        std::int64_t pixel) {
    auto a = std::make_shared<Analysis>();
    a->camera = camera;
    a->width = width;
    a->height = height;
    a->method = method;
    a->pixel = pixel;
    try {
        const std::vector<Ray> rays = PinholeProjection(camera, width, height).pixel_centre_rays();
        std::vector<Hit> hits(rays.size());
        auto detail = std::make_shared<TraceDetail>();
        detail->max_nodes = 300'000;
        detail->follow_ray = pixel;
        const auto tracer = make_tracer(method, params);
        tracer->set_scene(*scene);
        tracer->trace(rays, hits, Query::closest, detail.get());
        if (pixel >= 0 && std::size_t(pixel) < hits.size()) a->hit = hits[std::size_t(pixel)];
        a->detail = std::move(detail);
    } catch (const std::exception& e) {
        a->error = e.what();
    }
    return a;
}

/// Applies `set KEY VALUE` of a script to the UI settings; throws InputError.
void apply_setting(ViewerState& s, const std::string& key, const std::string& value) {
    UiSettings& ui = s.ui;
    EdacrtParams& p = ui.params;
    const auto number = [&] {
        try {
            std::size_t used = 0;
            const double v = std::stod(value, &used);
            if (used != value.size() || !std::isfinite(v)) throw std::invalid_argument(value);
            return v;
        } catch (const std::exception&) {
            throw InputError("'" + key + "' needs a number, got '" + value + "'");
        }
    };
    if (key == "method")
        ui.method = parse_method(value);
    else if (key == "embree-mode")
        ui.embree_mode = parse_embree_mode(value);
    else if (key == "integrator")
        ui.integrator = parse_integrator(value);
    else if (key == "primary")
        ui.primary = parse_primary_shading(value);
    else if (key == "spp")
        ui.spp_target = int(number());
    else if (key == "max-depth")
        ui.max_depth = int(number());
    else if (key == "ao-samples")
        ui.ao_samples = int(number());
    else if (key == "resolution")
        ui.resolution_scale = float(number());
    else if (key == "threads")
        ui.threads = int(number());
    else if (key == "seed")
        ui.seed = int(number());
    else if (key == "pause")
        ui.paused = number() != 0;
    else if (key == "preset")
        p = preset_params(value);
    else if (const ParamInfo* info = find_param(key))
        set_param(p, *info, value);
    else if (key == "exposure") {
        const auto exposure = float(number());
        validate_exposure(exposure);
        s.exposure = exposure;
    } else if (key == "scene")
        s.pending_loads.push_back(value);
    else if (key == "level")
        s.explorer_level = int(number());
    else if (key == "node")
        s.explorer_node = std::int32_t(number());
    else
        throw InputError("unknown setting '" + key + "'");
}

View parse_view(const std::string& name) {
    if (name == "render") return View::render;
    if (name == "box") return View::box_tests;
    if (name == "triangle") return View::triangle_tests;
    if (name == "depth") return View::depth;
    if (name == "order") return View::order_misses;
    throw InputError("unknown view '" + name + "' (render, box, triangle, depth, order)");
}

/// Saves the default framebuffer (what the window shows) as PNG.
void save_window(const std::string& path, int width, int height) {
    const std::size_t row = std::size_t(width) * 3;
    std::vector<std::uint8_t> pixels(row * std::size_t(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
    // OpenGL rows start at the bottom.
    for (std::size_t top = 0, bottom = std::size_t(height) - 1; top < bottom; ++top, --bottom)
        std::swap_ranges(pixels.begin() + std::ptrdiff_t(top * row),
                         pixels.begin() + std::ptrdiff_t((top + 1) * row),
                         pixels.begin() + std::ptrdiff_t(bottom * row));
    const std::filesystem::path out(path);
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    write_png_rgb8(out, pixels, width, height);
}

/// The shown frame's tone mapping, and what an EXR's header records about it.
ImageOutput save_settings(const ViewerState& s) {
    ImageOutput output;
    output.exposure = s.exposure;
    output.tone_map = ToneMap(s.tone_map);
    output.metadata = render_metadata(
        {"edacrt_viewer", s.scene ? s.scene->source : "", std::string(method_name(s.ui.method)),
         std::string(integrator_name(s.ui.integrator)), s.frame->spp, std::uint32_t(s.ui.seed),
         s.frame->seconds, s.camera.camera()});
    return output;
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
            if (c.verb == "wait-spp") {
                if (!waiting_) wait_start_ = Clock::now();
                waiting_ = true;
                if (shown_spp < std::stoi(c.args[0])) {
                    if (Clock::now() - wait_start_ > std::chrono::minutes(5))
                        throw InputError("script line " + std::to_string(c.line) +
                                         ": timed out waiting for " + c.args[0] + " spp");
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
            } else if (c.verb == "panel") {
                std::string name = c.args[0];
                std::replace(name.begin(), name.end(), '_', ' ');
                if (c.args[1] != "open" && c.args[1] != "closed")
                    throw InputError("script line " + std::to_string(c.line) +
                                     ": panel state is open or closed");
                s.collapse_panels.emplace_back(name, c.args[1] == "closed");
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
    load_into(s, options.scene);
    if (!s.scene) {
        std::cerr << "edacrt_viewer: error: " << s.scene_error << "\n";
        return 1;
    }
    const std::filesystem::path assets = options.assets_dir.empty()
                                             ? std::filesystem::path("assets")
                                             : std::filesystem::path(options.assets_dir);
    s.scene_list = scene_list(assets);

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
        RenderRequest submitted;
        std::uint64_t request_id = 0;
        std::shared_ptr<const Frame> uploaded, shown_last_frame;
        View uploaded_view = View::render;
        float heat_max = 1.0f;
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
            for (const auto& [name, closed] : std::exchange(s.collapse_panels, {}))
                ImGui::SetWindowCollapsed(name.c_str(), closed);
            const ImGuiIO& io = ImGui::GetIO();
            // The traversal debugger's pixel: a click on the image while picking, or the script.
            std::optional<ImVec2> pick = script ? script->take_pick() : std::nullopt;
            if (s.picking && !io.WantCaptureMouse && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
                pick = io.MousePos;
                s.picking = false;
            }
            if (pick && submitted.settings.width > 0) {
                const int x =
                    std::clamp(int(pick->x / io.DisplaySize.x * float(submitted.settings.width)), 0,
                               submitted.settings.width - 1);
                const int y =
                    std::clamp(int(pick->y / io.DisplaySize.y * float(submitted.settings.height)),
                               0, submitted.settings.height - 1);
                s.follow_pixel = std::int64_t(y) * submitted.settings.width + x;
                s.analysis_requested = true;
            } else if (!io.WantCaptureMouse) {
                const ImVec2 d = io.MouseDelta;
                if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) s.camera.orbit(d.x, d.y);
                if (ImGui::IsMouseDragging(ImGuiMouseButton_Right) ||
                    ImGui::IsMouseDragging(ImGuiMouseButton_Middle))
                    s.camera.pan(d.x, d.y, io.DisplaySize.y);
                if (io.MouseWheel != 0.0f) s.camera.zoom(io.MouseWheel);
            }
            if (!io.WantCaptureKeyboard) {
                // ImGui 1.86 indexes keys by the backend's (GLFW's) key codes.
                const auto key = [&](int k) { return ImGui::IsKeyDown(k) ? 1.0f : 0.0f; };
                const float forward = key(GLFW_KEY_W) - key(GLFW_KEY_S);
                const float right = key(GLFW_KEY_D) - key(GLFW_KEY_A);
                const float up = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
                if (forward != 0 || right != 0 || up != 0) s.camera.fly(forward, right, up, dt);
                if (ImGui::IsKeyPressed(GLFW_KEY_R)) s.camera.reset(s.scene_camera);
            }

            if (auto frame = worker.latest(); frame && frame->request == request_id) {
                s.render_error = frame->error;
                if (frame->error.empty()) s.frame = frame;
            }
            draw_render_panel(s);
            draw_params_panel(s);
            draw_stats_panel(s);
            draw_heatmap_panel(s, heat_max);
            draw_recursion_panel(s);
            draw_traversal_panel(s);

            // A changed setting, camera, scene or window size starts a new render.
            int width = 0, height = 0;
            glfwGetFramebufferSize(window, &width, &height);
            if (width > 0 && height > 0) {
                RenderRequest request = make_request(s, width, height);
                const bool changed = fit_resolution(s, request, submitted) &&
                                     (request_id == 0 || request != submitted);
                if (changed) {
                    // A new request restarts the film (pausing does not: see below).
                    submitted = request;
                    request_id = worker.submit(std::move(request));
                }
            }

            worker.set_paused(s.ui.paused);
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
                analysis = std::async(std::launch::async, analyse, s.scene, submitted.camera,
                                      submitted.settings.width, submitted.settings.height,
                                      s.ui.method, s.ui.params, s.follow_pixel);
            }
            if (analysis.valid() &&
                analysis.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
                s.analysis = analysis.get();
                s.analysis_running = false;
            }
            if (s.compare_requested && !comparison.valid()) {
                s.compare_requested = false;
                comparison =
                    std::async(std::launch::async, compare_methods, s.scene, s.camera.camera(),
                               submitted.settings.width, submitted.settings.height, s.ui.params);
            }
            if (comparison.valid() &&
                comparison.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
                s.comparison = comparison.get();
            if (s.save_requested && s.frame) {
                s.save_requested = false;
                try {
                    save_image(s.save_path, s.frame->image, save_settings(s));
                    s.status = "saved " + s.save_path;
                } catch (const std::exception& e) {
                    s.status = e.what();
                }
            }

            const bool heat =
                s.view != View::render && s.frame && s.frame->detail && uploaded_view == s.view;
            ImGui::Render();
            glViewport(0, 0, width, height);
            glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            if (s.frame) display.draw(heat, {s.exposure, s.tone_map}, heat_max, s.heat_log);
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

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
                    save_window(screenshot, width, height);
                    std::cout << "screenshot " << screenshot << " (" << width << "x" << height
                              << ", " << shown_spp << " spp, frame " << frame_number << ")\n";
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
