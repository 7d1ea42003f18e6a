// edacrt_viewer: the interactive viewer. See README.md ("The viewer").
#include <CLI/CLI.hpp>
#include <csignal>

#include "camera_flags.h"
#include "enum_flags.h"
#include "parse_command_line.h"
#include "scene/animation.h"
#include "viewer.h"
#include "viewer_state.h"

int main(int argc, char** argv) {
    // Past `ulimit -f` a save fails with EFBIG and is reported, instead of SIGXFSZ killing us.
    std::signal(SIGXFSZ, SIG_IGN);
    edacrt::app::ViewerOptions o;
    CLI::App app{"EDACRT Studio viewer: progressive rendering with divide-and-conquer ray tracing",
                 "edacrt_viewer"};
    app.add_option("scene", o.scene, "OBJ file or builtin:NAME")->capture_default_str();
    edacrt::flags::add_enum_option(app, "--method", o.method, edacrt::kMethods, "tracing method");
    edacrt::flags::add_enum_option(app, "--integrator", o.integrator, edacrt::kIntegrators,
                                   "integrator");
    app.add_option("--spp", o.spp, "samples per pixel to accumulate")
        ->check(CLI::Range(edacrt::app::setting_range("spp").min,
                           edacrt::app::setting_range("spp").max))
        ->capture_default_str();
    app.add_option("--width", o.width, "window width")->check(CLI::Range(64, 16384));
    app.add_option("--height", o.height, "window height")->check(CLI::Range(64, 16384));
    app.add_option("--frames", o.frames, "quit after this many frames (0: run until closed)")
        ->check(CLI::Range(0, 100000000));
    app.add_option("--screenshot", o.screenshot, "save the window as PNG before quitting");
    app.add_option("--script", o.script, "run UI actions from a file (see app/script.h)");
    edacrt::flags::add_camera_options(app, o.camera);
    app.add_flag("--hide-panels", o.hide_panels, "start with the panels hidden (Tab shows them)");
    app.add_option("--bookmarks", o.bookmarks,
                   "camera bookmarks file (default: $XDG_CONFIG_HOME/edacrt/bookmarks.json)");
    const std::string group = "Animation";
    app.add_option("--animate", o.animate,
                   "animate the scene (the scene may also be an animation file):\n" +
                       edacrt::animation_help())
        ->group(group);
    app.add_option("--time", o.time, "show the animation at this time in seconds")->group(group);
    app.add_flag("--play", o.play, "start playing (Space plays or pauses)")->group(group);
    app.add_option("--speed", o.speed, "animation seconds per second (0.05 to 4)")
        ->capture_default_str()
        ->group(group);
    edacrt::flags::add_enum_option(app, "--update", o.update, edacrt::kSceneUpdates,
                                   "how the tracer takes each frame")
        ->group(group);
    app.add_option("--shutter", o.shutter,
                   "motion blur: seconds of shutter around the frame's time (0: none)")
        ->group(group);
    if (const auto status = edacrt::flags::parse_command_line(app, argc, argv)) return *status;
    for (const char* flag : {"--time", "--play", "--speed", "--update", "--shutter"})
        if (app.count(flag) > 0) o.animation_flags.emplace_back(flag);
    // What escapes the viewer's own reports is a bug: an internal error, not an abort.
    return edacrt::flags::run_reporting_errors("edacrt_viewer",
                                               [&] { return edacrt::app::run_viewer(o); });
}
