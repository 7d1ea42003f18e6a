#pragma once
// Runs a viewer script (app/script.h) against the viewer's state, one step per frame.
#include <chrono>
#include <glm/vec2.hpp>
#include <optional>
#include <string>
#include <vector>

#include "script.h"
#include "viewer_state.h"

namespace edacrt::app {

/// What the frame just drawn shows, as the viewer knows it (the waits' conditions).
struct ShownFrame {
    int spp = 0;  // samples of the current request on screen (0 while a preview is shown)
    // The image region shows the view asked for (s.view) of the current request's latest
    // full-resolution pass.
    bool image_current = false;
};

/// Runs the script one step per frame; step() throws InputError naming the line that failed.
class ScriptRunner {
  public:
    explicit ScriptRunner(std::vector<ScriptCommand> commands) : commands_(std::move(commands)) {}

    /// Commands are left, or a save whose outcome the script has not checked yet.
    bool active() const { return next_ < commands_.size() || save_line_ > 0; }

    /// Called once per frame, after the frame is drawn.
    void step(ViewerState& s, const ShownFrame& shown, std::string& screenshot, bool& quit);

    /// A window position to pick (the traversal debugger), consumed by the viewer.
    std::optional<glm::vec2> take_pick() { return std::exchange(pick_, std::nullopt); }

    /// How long a wait may take before it fails the script (the `timeout` verb).
    static constexpr std::chrono::duration<double> kDefaultTimeout{300.0};

  private:
    /// True while `done` is false (the step ends there); fails the command once the timeout
    /// has passed since the wait began.
    bool waiting(bool done, const ScriptCommand& command, const std::string& what);

    std::vector<ScriptCommand> commands_;
    std::optional<glm::vec2> pick_;
    bool analysis_asked_ = false;
    bool compare_asked_ = false;
    std::size_t next_ = 0;
    int save_line_ = 0;  // the line of a save asked for and not checked yet
    int frames_left_ = -1;
    bool waiting_ = false;
    std::chrono::steady_clock::time_point wait_start_;
    std::chrono::duration<double> timeout_ = kDefaultTimeout;
    // wait-settled: the last frame's layout, and for how many frames it has not changed.
    std::string last_layout_;
    int same_layout_frames_ = 0;
};

/// The last frame's layout as JSON (the script's `layout FILE`), in window coordinates (ImGui's
/// units; `framebuffer_scale` converts them to screenshot pixels): `window` {w, h}, `image`,
/// `controls`, `analysis`, `timeline` (the layout's regions, {x, y, w, h}; empty when not
/// shown), `panels` (the panel windows as drawn, with `clipped_cells`), `items` (name to
/// rectangle), `tabs_open` and `errors_shown`.
std::string layout_json(const ViewerState& s);

}  // namespace edacrt::app
