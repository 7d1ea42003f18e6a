#pragma once
// The viewer's --script: UI actions, one per line, for headless tests and demos.
//   set KEY VALUE      a setting of app/settings_table.h (method, spp, max-depth, exposure,
//                      compare-spp, ...; the animation's time, play, speed, loop, update,
//                      shutter, play-scale), an EDACRT flag without "--" (set filter-skip off),
//                      preset NAME, scene PATH, animate SPEC, or the explorer's level, node,
//                      crop and step
//   view NAME          render | box | triangle | depth | order
//   wait-spp N         until the shown image has N samples per pixel (of the current settings)
//   wait-loaded        until the scenes asked for (set scene) are loaded and the render asked
//                      for has begun (its first frame or its error); fails the script with the
//                      error when the last load or that render failed
//   wait-error         until an error message is on screen (drawn by the panels in the last
//                      frame; with the panels hidden, one they would show: scene, resolution,
//                      render or animation) and prints it ("error shown: ...")
//   wait-settled       until the screen shows what was asked: the view of the current
//                      render's latest full-resolution pass, the tabs brought forward, and the
//                      panels, widgets and table columns unchanged for three frames
//   timeout S          the waits that follow fail the script after S seconds (default 300)
//   frames N           let N frames pass (demos; tests wait for a condition instead)
//   orbit DX DY        drag the camera by DX, DY pixels
//   tab NAME           bring a tab forward (NAME with '_' for spaces: Heat_map)
//   panels hidden|shown       hide all panels (Tab) or show them
//   analysis open|closed      expand or collapse the analysis area
//   help on|off        the help overlay
//   check-layout       fail unless every panel is inside the window, off the image region,
//                      with no table cell clipped (the last frame's layout)
//   layout FILE        write the last frame's layout as JSON (layout_json()): the window,
//                      the image region, the panels and the widgets the panels report, in
//                      window coordinates (times framebuffer_scale for screenshot pixels)
//   save-view FILE     save the image region as shown (.png or .jpg)
//   save-linear FILE   save the render (.exr, .pfm, .hdr linear; .png, .jpg tone-mapped)
//   write-command FILE write the `edacrt render` command that reproduces the view
//   bookmark NAME      save the view as the scene's bookmark NAME in the bookmarks file
//                      (--bookmarks), as the Camera tab's "save view" does
//   record             record the view's recursion (recursion explorer)
//   pick X Y           follow the camera ray under window position X, Y (traversal debugger)
//   pick-image U V     the same at fractions U, V (0 to 1) of the image region's width, height
//   wait-analysis      until the recording or the followed ray is ready
//   compare            time every method on the view (Statistics, Frames)
//   wait-compare       until the comparison is done
//   wait-played N      until N frames of the animation were rendered since it was loaded
//                      (set play 1 first; set time T shows time T, paused)
//   screenshot FILE    save the window as PNG
//   quit
// '#' starts a comment. Errors name the line: a bad number or `set` value, a save or write
// that fails, a render that fails while a wait-* waits for it, a wait that times out.
#include <string>
#include <string_view>
#include <vector>

namespace edacrt::app {

struct ScriptCommand {
    std::string verb;
    std::vector<std::string> args;
    std::vector<double> numbers;  // the arguments of verbs that take numbers, checked
    int line = 0;
};

/// Throws InputError ("FILE:LINE: ...") for unknown verbs, wrong argument counts or numbers
/// (naming the value).
std::vector<ScriptCommand> parse_script(std::string_view text, const std::string& source);

/// Reads and parses a script file.
std::vector<ScriptCommand> load_script(const std::string& path);

}  // namespace edacrt::app
