#include "viewer.h"

// glad before GLFW, so GLFW does not pull in the system GL header.
#include <glad/gl.h>
// clang-format off
#include <GLFW/glfw3.h>
// clang-format on
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <filesystem>
#include <iostream>
#include <optional>

#include "parse_command_line.h"
#include "script_runner.h"
#include "util/printable.h"
#include "viewer_jobs.h"
#include "viewer_loop.h"
#include "viewer_state.h"

namespace edacrt::app {

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
    // Animation flags without an animation are refused, as edacrt refuses --frames, --time and
    // --shutter.
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

    // Before ImGui's backend installs its own, which then calls this one: shortcuts are read
    // from these events (KeyPresses), not from the key state sampled once per frame.
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
        if (action == GLFW_RELEASE) return;
        static_cast<ViewerState*>(glfwGetWindowUserPointer(w))
            ->keys.press(key, mods, action == GLFW_REPEAT);
    });

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the same layout every start (and in tests)
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330");

    const int exit_code = run_frames(window, s, script, options);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return exit_code;
}

}  // namespace edacrt::app
