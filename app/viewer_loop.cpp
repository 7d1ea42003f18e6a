// The viewer's frame loop (app/viewer_loop.h): a Viewer whose frame is a list of named phases.
#include "viewer_loop.h"

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
#include <future>
#include <iostream>
#include <optional>
#include <tuple>

#include "command_line.h"
#include "display.h"
#include "frame_phases.h"
#include "panels/panels.h"
#include "render/film.h"
#include "render/image.h"
#include "render/image_format.h"
#include "render/render_metadata.h"
#include "script_runner.h"
#include "util/error.h"
#include "util/printable.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

using Clock = std::chrono::steady_clock;

/// Saves a region of the back buffer (what the window shows; x, y from the top-left, in framebuffer
/// pixels) as PNG or JPEG by the extension, creating the folder.
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
    save_srgb8(path, pixels, width, height);
}

/// The shown frame's tone mapping, and what an EXR's header records about it.
ImageOutput save_settings(const ViewerState& s) {
    ImageOutput output;
    output.exposure = s.exposure;
    output.tone_map = s.tone_map;
    output.metadata =
        render_metadata({"edacrt_viewer", s.scene ? s.scene->source : "",
                         std::string(enum_name(kMethods, s.ui.method)),
                         std::string(enum_name(kIntegrators, s.ui.integrator)), s.frame->spp,
                         std::uint32_t(s.ui.seed), s.frame->seconds, s.camera.camera()});
    return output;
}

/// Keys (while no text field has the keyboard): Tab or F1 hide the panels, H or ? the help, F12
/// saves the image, Esc quits, R resets the view, WASD/QE fly, +/- change the fly speed.
/// Shortcuts are the window's key
/// events since the last frame (s.keys), so a tap within one slow frame still counts; flying
/// reads whether a key is held. ImGui 1.86 indexes keys by GLFW's key codes.
void handle_keys(ViewerState& s, float dt, bool& quit) {
    const ImGuiIO& io = ImGui::GetIO();
    const KeyPresses& keys = s.keys;
    if (io.WantTextInput) return;
    if (keys.pressed(GLFW_KEY_ESCAPE)) quit = true;
    if (keys.pressed(GLFW_KEY_F12)) s.save_requested = ViewerState::Save::shown;
    if (io.WantCaptureKeyboard) return;
    if ((keys.count(GLFW_KEY_TAB) + keys.count(GLFW_KEY_F1)) % 2)
        s.panels_hidden = !s.panels_hidden;
    if ((keys.count(GLFW_KEY_H) + keys.count(GLFW_KEY_SLASH, GLFW_MOD_SHIFT)) % 2)
        s.show_help = !s.show_help;
    const auto key = [&](int k) { return ImGui::IsKeyDown(k) ? 1.0f : 0.0f; };
    const float forward = key(GLFW_KEY_W) - key(GLFW_KEY_S);
    const float right = key(GLFW_KEY_D) - key(GLFW_KEY_A);
    const float up = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
    // +/- the fly speed; with Ctrl, the font (Ctrl 0: its default).
    const auto plus_minus = [&](int mods, int without) {
        return keys.count(GLFW_KEY_EQUAL, mods, false, without) +
               keys.count(GLFW_KEY_KP_ADD, mods, false, without) -
               keys.count(GLFW_KEY_MINUS, mods, false, without) -
               keys.count(GLFW_KEY_KP_SUBTRACT, mods, false, without);
    };
    const int larger = plus_minus(GLFW_MOD_CONTROL, 0);
    if (larger != 0) s.font_scale = step_font_scale(s.font_scale, larger);
    if (keys.pressed(GLFW_KEY_0, GLFW_MOD_CONTROL)) s.font_scale = 1.0f;
    // '+' is Shift + '=' on most layouts: '=' alone counts too.
    const int faster = plus_minus(0, GLFW_MOD_CONTROL);
    if (faster != 0)
        s.fly_speed_step = std::clamp(s.fly_speed_step + faster, -kFlySpeedSteps, kFlySpeedSteps);
    if ((forward != 0 || right != 0 || up != 0) && s.scene) {
        const float step = fly_speed(s.scene->bounds(), s.fly_speed_step) * dt;
        change_camera(s, [&] { s.camera.fly(forward, right, up, step); });
    }
    if (keys.pressed(GLFW_KEY_R)) change_camera(s, [&] { s.camera.reset(s.scene_camera); });
    if (s.playback.frames) {  // the timeline: Space plays or pauses, arrows step 1/24 s each
        if (keys.count(GLFW_KEY_SPACE) % 2) toggle_play(s);
        const int steps = keys.count(GLFW_KEY_RIGHT, 0, true) - keys.count(GLFW_KEY_LEFT, 0, true);
        if (steps != 0) seek(s, s.playback.time + steps / 24.0);
    }
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

/// The frame loop as named phases (STYLE 20): each phase is a function and owns the part of the
/// loop's state it changes; frame() is the list of phases.
class Viewer {
  public:
    Viewer(GLFWwindow* window, ViewerState& state, std::optional<ScriptRunner>& script,
           const ViewerOptions& options)
        : window_(window), s_(state), script_(script), options_(options) {}
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;
    ~Viewer() { wait_for_jobs(); }

    /// Runs frames until the window is closed, the script or --frames end, or an error; returns the
    /// exit code.
    int run() {
        while (!glfwWindowShouldClose(window_) && !quit_) frame();
        wait_for_jobs();
        if (options_.frames > 0 || script_) {  // headless runs report the UI's frame rate
            const double seconds =
                std::chrono::duration<double>(Clock::now() - clock_.first).count();
            std::cout << clock_.frames << " frames in " << seconds << " s ("
                      << double(clock_.frames) / seconds << " fps), slowest frame "
                      << clock_.slowest * 1e3f << " ms\n";
        }
        return exit_code_;
    }

  private:
    void frame() {
        input();
        sync_worker(s_, worker_.latest(), request_id_, dt_);
        panels();
        submit();
        jobs();
        upload();
        draw();
        outputs();
        script();
        glfwSwapBuffers(window_);
    }

    /// Input: window events, dropped and asked-for scenes, the layout, picks, drags and keys.
    void input() {
        glfwPollEvents();
        const auto now = Clock::now();
        dt_ = std::chrono::duration<float>(now - clock_.last).count();
        clock_.last = now;
        if (clock_.frames > 5) clock_.slowest = std::max(clock_.slowest, dt_);
        poll_loads(s_);

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        float content_scale_y = 1.0f;  // the same as x on every platform GLFW supports
        glfwGetWindowContentScale(window_, &s_.content_scale, &content_scale_y);
        ImGui::GetIO().FontGlobalScale = s_.font_scale * s_.content_scale;
        ImGui::NewFrame();
        const ImGuiIO& io = ImGui::GetIO();
        s_.layout = compute_layout({io.DisplaySize.x, io.DisplaySize.y, ImGui::GetFontSize(),
                                    ImGui::GetFrameHeight(), s_.panels_hidden, s_.analysis_open,
                                    bool(s_.playback.frames), s_.analysis_share});
        const Rect& image = s_.layout.image;
        const auto in_image = [&](ImVec2 p) {
            return p.x >= image.x && p.y >= image.y && p.x < image.right() && p.y < image.bottom();
        };
        // The traversal debugger's pixel: a click on the image while picking, or the script.
        // Picking stays on, pixel after pixel; a drag still orbits (a click is a release that
        // did not drag).
        std::optional<ImVec2> pick;
        if (const auto p = script_ ? script_->take_pick() : std::nullopt) pick = ImVec2(p->x, p->y);
        if (s_.picking && !io.WantCaptureMouse && in_image(io.MousePos) &&
            in_image(io.MouseClickedPos[ImGuiMouseButton_Left]) &&
            ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
            io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] <
                io.MouseDragThreshold * io.MouseDragThreshold)
            pick = io.MousePos;
        const RenderSettings& rendered = s_.submitted.settings;
        if (pick && rendered.width > 0 && in_image(*pick)) {
            const int x = std::clamp(int((pick->x - image.x) / image.w * float(rendered.width)), 0,
                                     rendered.width - 1);
            const int y = std::clamp(int((pick->y - image.y) / image.h * float(rendered.height)), 0,
                                     rendered.height - 1);
            s_.follow_pixel = std::int64_t(y) * rendered.width + x;
            s_.analysis_requested = true;
        } else if (s_.region_picking && !io.WantCaptureMouse) {
            // The explorer's region: a left drag on the image, instead of moving the camera.
            const ImVec2 a = io.MouseClickedPos[ImGuiMouseButton_Left], b = io.MousePos;
            if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && in_image(a)) {
                const auto u = [&](float x) {
                    return std::clamp((x - image.x) / image.w, 0.0f, 1.0f);
                };
                const auto v = [&](float y) {
                    return std::clamp((y - image.y) / image.h, 0.0f, 1.0f);
                };
                const ImageRegion r{u(std::min(a.x, b.x)), v(std::min(a.y, b.y)),
                                    u(std::max(a.x, b.x)), v(std::max(a.y, b.y))};
                if (!r.empty()) {
                    s_.explorer_region = r;
                    s_.explorer_crop = true;
                    s_.analysis_requested = true;
                    s_.region_picking = false;
                }
            }
        } else if (!io.WantCaptureMouse) {
            // Drags that start on the image move the camera.
            const ImVec2 d = io.MouseDelta;
            const auto drag = [&](ImGuiMouseButton b) {
                return ImGui::IsMouseDragging(b) && in_image(io.MouseClickedPos[b]);
            };
            const bool inside = s_.scene && s_.scene->bounds().contains(s_.camera.camera().eye);
            change_camera(s_, [&] {
                for (const int button : {0, 1, 2}) {
                    if (!drag(button) || (d.x == 0.0f && d.y == 0.0f)) continue;
                    switch (drag_action(button, io.KeyShift, inside)) {
                        case DragAction::orbit:
                            s_.camera.orbit(d.x, d.y);
                            break;
                        case DragAction::look:
                            s_.camera.look(d.x, d.y);
                            break;
                        case DragAction::pan:
                            s_.camera.pan(d.x, d.y, image.h);
                            break;
                    }
                }
                if (io.MouseWheel != 0.0f && in_image(io.MousePos)) s_.camera.zoom(io.MouseWheel);
            });
            // A double click on the image orbits about the surface point under it.
            if (!s_.picking && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) &&
                in_image(io.MousePos))
                orbit_about_pixel(s_, (io.MousePos.x - image.x) / image.w,
                                  (io.MousePos.y - image.y) / image.h);
        }
        handle_keys(s_, dt_, quit_);
        s_.keys.clear();
    }

    /// Panels: ImGui's widgets, which show the state and take its edits.
    void panels() {
        s_.placements.clear();
        s_.items.clear();
        s_.tabs_open.clear();
        s_.errors_shown.clear();
        s_.recursion_shown = false;
        draw_controls(s_);
        draw_analysis(s_, uploads_.heat_max);
        draw_timeline(s_);
        draw_help(s_);
        draw_heat_readout(s_);
        draw_region(s_);
        draw_loading(s_);
    }

    /// Submit: a changed setting, camera, scene or image region starts a new render.
    void submit() {
        const ImGuiIO& io = ImGui::GetIO();
        glfwGetFramebufferSize(window_, &screen_.width, &screen_.height);
        const float scale_x = io.DisplaySize.x > 0 ? float(screen_.width) / io.DisplaySize.x : 1.0f;
        const float scale_y =
            io.DisplaySize.y > 0 ? float(screen_.height) / io.DisplaySize.y : 1.0f;
        s_.window_width = io.DisplaySize.x;
        s_.window_height = io.DisplaySize.y;
        s_.framebuffer_scale_x = scale_x;
        s_.framebuffer_scale_y = scale_y;
        screen_.region = to_pixels(s_.layout.image, scale_x, scale_y);
        if (auto request =
                changed_request(s_, screen_.region.w, screen_.region.h, request_id_ == 0)) {
            // A new request restarts the film (pausing does not: see jobs()).
            s_.submitted = *request;
            request_id_ = worker_.submit(std::move(*request));
            s_.render_error.clear();  // the previous request's
            s_.render_answered = false;
        }
        const RenderRequest& r = s_.submitted;
        s_.command_line = render_command_line(
            {program_, s_.scene_path, bool(r.animation), s_.animation_spec, r.time, r.update,
             r.shutter, r.method, r.embree_mode, r.params, r.settings, r.camera, r.spp_target,
             s_.exposure, s_.tone_map, timestamped(s_, ".png")});
    }

    /// Jobs: the comparison and the recording, run off the UI thread, started and collected.
    void jobs() {
        // The render pauses while methods are compared: their timings get the cores.
        s_.comparing = jobs_.comparison.valid();
        worker_.set_paused(s_.ui.paused || s_.comparing);
        const RenderRequest& submitted = s_.submitted;
        if (s_.analysis_requested && !jobs_.analysis.valid() && s_.scene &&
            submitted.settings.width > 0) {
            s_.analysis_requested = false;
            s_.analysis_running = true;
            jobs_.analysis = std::async(std::launch::async, analyse, submitted, s_.follow_pixel,
                                        s_.explorer_crop, s_.explorer_region, s_.batch, s_.against);
        }
        if (ready(jobs_.analysis)) {
            s_.analysis = jobs_.analysis.get();
            s_.analysis_running = false;
        }
        if (s_.compare_requested && !jobs_.comparison.valid()) {
            s_.compare_requested = false;
            worker_.set_paused(true);
            // An animation's frame is also refitted from the one 1/24 s before (after, at the
            // start).
            std::shared_ptr<const Scene> previous;
            const double t = s_.playback.time;
            if (s_.playback.frames) try {
                    previous = s_.playback.frames->at(t >= 1.0 / 24 ? t - 1.0 / 24 : t + 1.0 / 24);
                    s_.playback.compared_time = s_.playback.time;
                } catch (const std::exception& e) {
                    s_.playback.error = e.what();
                }
            s_.compared_scene = s_.scene_number;
            jobs_.comparison =
                std::async(std::launch::async, compare_methods, s_.scene, previous,
                           submitted.camera, submitted.settings.width, submitted.settings.height,
                           s_.compare_spp, submitted.settings.seed, s_.ui.params, &worker_);
            s_.comparing = true;
        }
        if (ready(jobs_.comparison)) s_.comparison = jobs_.comparison.get();
    }

    /// Upload: the newest pass (of the request in force) or its heat map, and the explorer's tint,
    /// each only when it changed.
    void upload() {
        Uploads& u = uploads_;
        if (s_.frame && s_.frame != u.frame) {
            display_.upload_render(s_.frame->image);
            u.frame = s_.frame;
        }
        // The heat map of the analysed batch (the frame's camera rays, or a recorded batch),
        // or of the recursion it is compared with, or of their difference.
        const HeatImage heat = heat_image(s_);
        if (!heat.pixels.empty() &&
            (heat.source != u.heat_source || s_.view != u.view || s_.heat_of != u.heat_of)) {
            const std::vector<float> values = heat.values(s_.view);
            float largest = 0.0f;
            for (const float v : values) largest = std::max(largest, std::abs(v));
            u.heat_max = std::max(1.0f, largest);
            display_.upload_heat(values, heat.width, heat.height);
            u.heat_source = heat.source;
            u.view = s_.view;
            u.heat_of = s_.heat_of;
            u.heat_difference = heat.difference();
        }
        // The selected node's pixels, and in step-through the hits found so far.
        u.tint = s_.recursion_shown && s_.explorer_tint && s_.analysis && !s_.analysis_stale &&
                 s_.analysis->detail && !s_.analysis->detail->nodes.empty();
        if (u.tint) {
            const int step = s_.stepping ? s_.step : -1;
            const auto key = std::tuple(s_.analysis.get(), s_.explorer_node, step);
            if (key != u.tint_key) {
                display_.upload_tint(explorer_tint(*s_.analysis, s_.explorer_node, step),
                                     s_.analysis->width, s_.analysis->height);
                u.tint_key = key;
            }
        }
        u.heat = !heat.pixels.empty() && heat.source == u.heat_source && u.view == s_.view &&
                 u.heat_of == s_.heat_of;
    }

    /// Draw: the image in its region (the render has the region's aspect), the tint, and (in
    /// outputs(), after a save of the image alone) the UI.
    void draw() {
        ImGui::Render();
        const PixelRect& region = screen_.region;
        glViewport(0, 0, screen_.width, screen_.height);
        glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glViewport(region.x, screen_.height - region.y - region.h, region.w, region.h);
        if (s_.frame)
            display_.draw(uploads_.heat, {s_.exposure, s_.tone_map}, uploads_.heat_max, s_.heat_log,
                          uploads_.heat_difference);
        if (uploads_.tint) display_.draw_tint();
        glViewport(0, 0, screen_.width, screen_.height);
    }

    /// Outputs: the saves asked for (the image region as shown, with or without the UI drawn over
    /// it, or the linear render), the UI itself, and the layout's problems.
    void outputs() {
        const PixelRect& region = screen_.region;
        const auto save_shown = [&] {
            const std::string path = s_.save_path.empty() ? timestamped(s_, ".png") : s_.save_path;
            check_output_spares_inputs(s_, path, "save-view");
            save_framebuffer(path, region.x, region.y, region.w, region.h, screen_.height);
            s_.status = "saved " + path;
            std::cout << "saved " << printable(path) << "\n";
        };
        const auto save = std::exchange(s_.save_requested, ViewerState::Save::none);
        const auto save_failed = [&](const std::exception& e) {
            s_.status = s_.save_error = e.what();
            std::cerr << "edacrt_viewer: error: " << printable(e.what()) << "\n";
        };
        try {
            if (save == ViewerState::Save::shown && !s_.save_overlays) save_shown();
            if (save == ViewerState::Save::linear && !s_.frame)
                throw InputError("no image to save yet");
            if (save == ViewerState::Save::linear) {
                const std::string path =
                    s_.save_path.empty() ? timestamped(s_, ".exr") : s_.save_path;
                check_output_spares_inputs(s_, path, "save-linear");
                save_image(path, s_.frame->image, save_settings(s_));
                s_.status = "saved " + path;
                std::cout << "saved " << printable(path) << "\n";
            }
        } catch (const std::exception& e) {
            save_failed(e);
        }
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        try {
            if (save == ViewerState::Save::shown && s_.save_overlays) save_shown();
        } catch (const std::exception& e) {
            save_failed(e);
        }
        if (save != ViewerState::Save::none) s_.save_path.clear();
        const ImGuiIO& io = ImGui::GetIO();
        s_.layout_problems =
            layout_problems(s_.layout, io.DisplaySize.x, io.DisplaySize.y, s_.placements);
    }

    /// Script: the script's next step, --frames and the screenshot either asks for.
    void script() {
        ++clock_.frames;
        std::string screenshot;
        // A pass counts as shown once it has been on screen for a whole frame: ImGui sizes new
        // table columns from the previous frame's contents.
        const bool settled = s_.frame && s_.frame == shown_last_frame_;
        shown_last_frame_ = s_.frame;
        // While a scene asked for is read, the old scene's passes are not what was asked.
        const bool current = s_.frame && s_.frame->request == request_id_ && !s_.frame->preview &&
                             !s_.loading && s_.pending_loads.empty();
        const int shown_spp = settled && current ? s_.frame->spp : 0;
        // The image region shows the view asked for of the newest pass received.
        const bool image_current =
            current && uploads_.frame == s_.frame && (s_.view == View::render || uploads_.heat);
        const PixelRect& region = screen_.region;
        try {
            if (script_) {
                script_->step(s_, {shown_spp, image_current}, screenshot, quit_);
                if (!script_->active() && options_.frames == 0) quit_ = true;
            }
            // --frames: at the last frame, once a full-resolution pass is on screen.
            if (options_.frames > 0 && clock_.frames >= options_.frames && shown_spp > 0 &&
                (!script_ || !script_->active())) {
                if (!options_.screenshot.empty()) screenshot = options_.screenshot;
                quit_ = true;
            }
            if (!screenshot.empty()) {
                check_output_spares_inputs(s_, screenshot, "screenshot");
                save_framebuffer(screenshot, 0, 0, screen_.width, screen_.height, screen_.height);
                std::cout << "screenshot " << printable(screenshot) << " (" << screen_.width << "x"
                          << screen_.height << ", " << shown_spp << " spp, frame " << clock_.frames
                          << ", image region " << region.x << " " << region.y << " " << region.w
                          << " " << region.h << ")\n";
            }
        } catch (const std::exception& e) {
            std::cerr << "edacrt_viewer: error: " << printable(e.what()) << "\n";
            exit_code_ = 1;
            quit_ = true;
        }
    }

    /// The jobs read the state and the worker: both must outlive them.
    void wait_for_jobs() {
        if (jobs_.comparison.valid()) jobs_.comparison.wait();
        if (jobs_.analysis.valid()) jobs_.analysis.wait();
    }

    template <typename T>
    static bool ready(const std::future<T>& job) {
        return job.valid() && job.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
    }

    GLFWwindow* window_;
    ViewerState& s_;
    std::optional<ScriptRunner>& script_;
    const ViewerOptions& options_;
    Display display_;
    RenderWorker worker_;
    // input: the frame clock.
    struct {
        Clock::time_point first = Clock::now(), last = first;
        float slowest = 0.0f;  // seconds, after the first few frames (start-up)
        int frames = 0;
    } clock_;
    float dt_ = 0.0f;
    bool quit_ = false;
    // submit: the request in force, and the framebuffer and image region it was made for; the
    // edacrt its command line names.
    const std::string program_ = edacrt_program(this_executable());
    std::uint64_t request_id_ = 0;
    struct {
        int width = 0, height = 0;
        PixelRect region;
    } screen_;
    // jobs: the comparison and the recording in flight.
    struct {
        std::future<std::vector<MethodTotals>> comparison;
        std::future<std::shared_ptr<const Analysis>> analysis;
    } jobs_;
    // upload: what the textures hold.
    struct Uploads {
        std::shared_ptr<const Frame> frame;
        View view = View::render;                 // of the heat map
        std::shared_ptr<const void> heat_source;  // HeatImage::source of the heat map
        HeatOf heat_of = HeatOf::a;
        bool heat_difference = false;  // signed values: B - A
        float heat_max = 1.0f;         // the largest |value|
        bool heat = false;             // the heat map of the view asked for is uploaded
        bool tint = false;             // the explorer's tint is shown
        std::tuple<const Analysis*, std::int32_t, int> tint_key{nullptr, -1, -1};
    } uploads_;
    // script: the pass on screen in the last frame.
    std::shared_ptr<const Frame> shown_last_frame_;
    int exit_code_ = 0;
};

}  // namespace

int run_frames(GLFWwindow* window, ViewerState& state, std::optional<ScriptRunner>& script,
               const ViewerOptions& options) {
    Viewer viewer(window, state, script, options);
    return viewer.run();
}

}  // namespace edacrt::app
