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

#include "command_line.h"
#include "display.h"
#include "panels/panels.h"
#include "parse_command_line.h"
#include "render/camera_options.h"
#include "render/default_camera.h"
#include "render/film.h"
#include "render/image.h"
#include "render/image_format.h"
#include "render/render_memory.h"
#include "render/render_metadata.h"
#include "render/wavefront.h"
#include "script.h"
#include "script_runner.h"
#include "util/error.h"
#include "util/printable.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

using Clock = std::chrono::steady_clock;

/// Saves a region of the back buffer (what the window shows; x, y from the top-left, in
/// framebuffer pixels) as PNG or JPEG by the extension, creating the folder.
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
    if (forward != 0 || right != 0 || up != 0)
        change_camera(s, [&] { s.camera.fly(forward, right, up, dt); });
    if (ImGui::IsKeyPressed(GLFW_KEY_R)) change_camera(s, [&] { s.camera.reset(s.scene_camera); });
    if (s.playback.frames) {  // the timeline: Space plays or pauses, arrows step 1/24 s
        if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) toggle_play(s);
        if (ImGui::IsKeyPressed(GLFW_KEY_LEFT)) seek(s, s.playback.time - 1.0 / 24);
        if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT)) seek(s, s.playback.time + 1.0 / 24);
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

}  // namespace

int run_viewer(const ViewerOptions& options) {
    ViewerState s;
    std::optional<ScriptRunner> script;
    try {
        if (!options.script.empty()) script.emplace(load_script(options.script));
        s.script_path = options.script;
    } catch (const std::exception& e) {
        std::cerr << "edacrt_viewer: error: " << printable(e.what()) << "\n";
        return 1;
    }
    s.panels_hidden = options.hide_panels;
    load_into(s, options.scene, options.camera, options.animate);
    if (!s.scene) {
        std::cerr << "edacrt_viewer: error: " << printable(s.scene_error) << "\n";
        return 1;
    }
    // Animation flags without an animation are refused, as edacrt refuses --frames, --time
    // and --shutter.
    if (const std::string given = animation_flags(options.settings);
        !s.playback.frames && !given.empty()) {
        std::cerr << "edacrt_viewer: error: " << given
                  << (given.find(',') == std::string::npos ? " needs" : " need")
                  << " an animated scene (--animate, or an animation file)\n";
        return flags::kExitUsageError;
    }
    try {
        apply_settings(s, options.settings);
    } catch (const std::exception& e) {  // checked while parsing: only a frame that fails
        std::cerr << "edacrt_viewer: error: " << printable(e.what()) << "\n";
        return 1;
    }
    s.bookmarks_path = options.bookmarks.empty() ? Bookmarks::default_path() : options.bookmarks;
    if (!s.bookmarks_path.empty()) {
        const std::vector<std::string> problems = s.bookmarks.load(s.bookmarks_path);
        for (const std::string& p : problems)
            std::cerr << "edacrt_viewer: warning: " << printable(p) << "\n";
        if (!problems.empty()) {
            const std::string what_happens_next =
                s.bookmarks.unreadable()
                    ? "; it is left as it is and bookmarks are not saved"
                    : "; the file is moved to a .bak before bookmarks are next saved";
            s.status = problems.front() +
                       (problems.size() > 1
                            ? " (and " + std::to_string(problems.size() - 1) + " more on stderr)"
                            : std::string()) +
                       what_happens_next;
            std::cerr << "edacrt_viewer: warning: " << printable(s.bookmarks_path) << ":"
                      << what_happens_next.substr(1) << "\n";
        }
    }
    const std::filesystem::path assets = options.assets_dir.empty()
                                             ? std::filesystem::path("assets")
                                             : std::filesystem::path(options.assets_dir);
    s.scene_list = scene_catalog(assets);

    glfwSetErrorCallback([](int code, const char* text) {
        std::cerr << "edacrt_viewer: GLFW error " << code << ": " << printable(text ? text : "")
                  << "\n";
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
                                       ImGui::GetFrameHeight(), s.panels_hidden, s.analysis_open,
                                       bool(s.playback.frames)});
            const Rect& image = s.layout.image;
            const auto in_image = [&](ImVec2 p) {
                return p.x >= image.x && p.y >= image.y && p.x < image.right() &&
                       p.y < image.bottom();
            };
            // The traversal debugger's pixel: a click on the image while picking, or the script.
            std::optional<ImVec2> pick;
            if (const auto p = script ? script->take_pick() : std::nullopt)
                pick = ImVec2(p->x, p->y);
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
                change_camera(s, [&] {
                    if (drag(ImGuiMouseButton_Left)) s.camera.orbit(d.x, d.y);
                    if (drag(ImGuiMouseButton_Right) || drag(ImGuiMouseButton_Middle))
                        s.camera.pan(d.x, d.y, image.h);
                    if (io.MouseWheel != 0.0f && in_image(io.MousePos))
                        s.camera.zoom(io.MouseWheel);
                });
            }
            handle_keys(s, dt, quit);

            if (auto frame = worker.latest(); frame && frame->request == request_id) {
                s.render_error = frame->error;
                s.render_answered = true;
                if (!frame->error.empty() && s.playback.playing) {  // no frame to wait for
                    s.playback.playing = false;
                    s.playback.error = frame->error;
                }
                if (frame->error.empty() && frame != s.frame) {
                    if (frame->preview) s.convergence.clear();
                    if (!frame->preview && s.frame && !s.frame->preview &&
                        s.frame->request == frame->request && s.frame->spp < frame->spp)
                        s.convergence.push_back(
                            {frame->seconds, frame->spp,
                             relative_rms_change(frame->image, s.frame->image)});
                    s.frame = frame;
                    record_frame_time(s, *frame, submitted.method);
                }
            }
            // Playing: the next frame once this one's first full pass is shown.
            advance_playback(s, s.frame && s.frame->request == request_id && !s.frame->preview, dt);
            s.analysis_stale = s.analysis && analysis_stale(*s.analysis, submitted);
            s.placements.clear();
            s.items.clear();
            s.tabs_open.clear();
            s.errors_shown.clear();
            s.recursion_shown = false;
            draw_controls(s);
            draw_analysis(s, heat_max);
            draw_timeline(s);
            draw_help(s);
            draw_heat_readout(s);

            // A changed setting, camera, scene or image region starts a new render.
            int fb_width = 0, fb_height = 0;
            glfwGetFramebufferSize(window, &fb_width, &fb_height);
            const float scale_x = io.DisplaySize.x > 0 ? float(fb_width) / io.DisplaySize.x : 1.0f;
            const float scale_y = io.DisplaySize.y > 0 ? float(fb_height) / io.DisplaySize.y : 1.0f;
            s.window_width = io.DisplaySize.x;
            s.window_height = io.DisplaySize.y;
            s.framebuffer_scale_x = scale_x;
            s.framebuffer_scale_y = scale_y;
            const PixelRect region = to_pixels(image, scale_x, scale_y);
            if (region.w > 0 && region.h > 0) {
                RenderRequest request = make_request(s, region.w, region.h);
                const bool changed = fit_resolution(s, request, submitted) &&
                                     (request_id == 0 || request != submitted);
                if (changed) {
                    // A new request restarts the film (pausing does not: see below).
                    submitted = request;
                    request_id = worker.submit(std::move(request));
                    s.render_error.clear();  // the previous request's
                    s.render_answered = false;
                }
            }
            s.command_line = render_command_line(
                {s.scene_path, bool(submitted.animation), s.animation_spec, submitted.time,
                 submitted.update, submitted.shutter, submitted.method, submitted.embree_mode,
                 submitted.params, submitted.settings, submitted.camera, submitted.spp_target,
                 s.exposure, s.tone_map, timestamped(s, ".png")});

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
                // An animation's frame is also refitted from the one 1/24 s before (after, at
                // the start).
                std::shared_ptr<const Scene> previous;
                const double t = s.playback.time;
                if (s.playback.frames) try {
                        previous =
                            s.playback.frames->at(t >= 1.0 / 24 ? t - 1.0 / 24 : t + 1.0 / 24);
                        s.playback.compared_time = s.playback.time;
                    } catch (const std::exception& e) {
                        s.playback.error = e.what();
                    }
                comparison = std::async(std::launch::async, compare_methods, s.scene, previous,
                                        submitted.camera, submitted.settings.width,
                                        submitted.settings.height, s.compare_spp,
                                        submitted.settings.seed, s.ui.params, &worker);
                s.comparing = true;
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
                check_output_spares_inputs(s, path, "save-view");
                save_framebuffer(path, region.x, region.y, region.w, region.h, fb_height);
                s.status = "saved " + path;
                std::cout << "saved " << printable(path) << "\n";
            };
            const auto save = std::exchange(s.save_requested, ViewerState::Save::none);
            const auto save_failed = [&](const std::exception& e) {
                s.status = s.save_error = e.what();
                std::cerr << "edacrt_viewer: error: " << printable(e.what()) << "\n";
            };
            try {
                if (save == ViewerState::Save::shown && !s.save_overlays) save_shown();
                if (save == ViewerState::Save::linear && !s.frame)
                    throw InputError("no image to save yet");
                if (save == ViewerState::Save::linear) {
                    const std::string path =
                        s.save_path.empty() ? timestamped(s, ".exr") : s.save_path;
                    check_output_spares_inputs(s, path, "save-linear");
                    save_image(path, s.frame->image, save_settings(s));
                    s.status = "saved " + path;
                    std::cout << "saved " << printable(path) << "\n";
                }
            } catch (const std::exception& e) {
                save_failed(e);
            }
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            try {
                if (save == ViewerState::Save::shown && s.save_overlays) save_shown();
            } catch (const std::exception& e) {
                save_failed(e);
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
            const bool current = s.frame && s.frame->request == request_id && !s.frame->preview;
            const int shown_spp = settled && current ? s.frame->spp : 0;
            // The image region shows the view asked for of the newest pass received.
            const bool image_current = current && uploaded == s.frame && uploaded_view == s.view &&
                                       (s.view == View::render || heat);
            try {
                if (script) {
                    script->step(s, {shown_spp, image_current}, screenshot, quit);
                    if (!script->active() && options.frames == 0) quit = true;
                }
                // --frames: at the last frame, once a full-resolution pass is on screen.
                if (options.frames > 0 && frame_number >= options.frames && shown_spp > 0 &&
                    (!script || !script->active())) {
                    if (!options.screenshot.empty()) screenshot = options.screenshot;
                    quit = true;
                }
                if (!screenshot.empty()) {
                    check_output_spares_inputs(s, screenshot, "screenshot");
                    save_framebuffer(screenshot, 0, 0, fb_width, fb_height, fb_height);
                    std::cout << "screenshot " << printable(screenshot) << " (" << fb_width << "x"
                              << fb_height << ", " << shown_spp << " spp, frame " << frame_number
                              << ", image region " << region.x << " " << region.y << " " << region.w
                              << " " << region.h << ")\n";
                }
            } catch (const std::exception& e) {
                std::cerr << "edacrt_viewer: error: " << printable(e.what()) << "\n";
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
