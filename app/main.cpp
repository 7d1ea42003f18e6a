// edacrt_viewer: the interactive viewer. See README.md ("The viewer").
#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>

#include "camera_flags.h"
#include "parse_command_line.h"
#include "scene/animation.h"
#include "script.h"
#include "setting_flags.h"
#include "viewer.h"

int main(int argc, char** argv) {
    // Past `ulimit -f` a save fails with EFBIG and is reported, instead of SIGXFSZ killing us.
    std::signal(SIGXFSZ, SIG_IGN);
    edacrt::app::ViewerOptions o;
    CLI::App app{"EDACRT Studio viewer: progressive rendering with divide-and-conquer ray tracing",
                 "edacrt_viewer"};
    app.add_option("scene", o.scene, "OBJ file or builtin:NAME")->capture_default_str();
    edacrt::app::add_setting_flags(app, o.settings);
    app.add_option("--width", o.width, "window width")->check(CLI::Range(64, 16384));
    app.add_option("--height", o.height, "window height")->check(CLI::Range(64, 16384));
    app.add_option("--frames", o.frames, "quit after this many frames (0: run until closed)")
        ->check(CLI::Range(0, 100000000));
    app.add_option("--screenshot", o.screenshot, "save the window as PNG before quitting");
    app.add_option("--script", o.script, "run UI actions from a file (--script-help lists them)");
    app.add_flag_callback(
        "--script-help",
        [] {
            std::cout << edacrt::app::script_help();
            throw CLI::Success();
        },
        "list the script's commands and exit");
    edacrt::flags::add_camera_options(app, o.camera);
    app.add_flag("--hide-panels", o.hide_panels, "start with the panels hidden (Tab shows them)");
    app.add_option("--bookmarks", o.bookmarks,
                   "camera bookmarks file (default: $XDG_CONFIG_HOME/edacrt/bookmarks.json)");
    app.add_option("--animate", o.animate,
                   "animate the scene (the scene may also be an animation file):\n" +
                       edacrt::animation_help())
        ->group("Animation");
    if (const auto status = edacrt::flags::parse_command_line(app, argc, argv)) return *status;
    // What escapes the viewer's own reports is a bug: an internal error, not an abort.
    return edacrt::flags::run_reporting_errors("edacrt_viewer",
                                               [&] { return edacrt::app::run_viewer(o); });
}
