#pragma once
// Runs a viewer script (app/script.h) against the viewer's state, one step per frame.
#include <chrono>
#include <glm/vec2.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "script.h"
#include "viewer_state.h"

namespace edacrt::app {

/// What the frame just drawn shows, as the viewer knows it (the waits' conditions).
struct ShownFrame {
    int spp = 0;  // samples of the current request on screen (0 while a preview is
                  // shown)
    // The image region shows the view asked for (s.view) of the current request's latest
    // full-resolution pass.
    bool image_current = false;
};

/// What a verb's step works on: the state, what the frame shows, the command, and the frame's
/// outputs (a screenshot to take, quitting).
struct ScriptStep {
    ViewerState& s;
    const ShownFrame& shown;
    const ScriptCommand& c;
    std::string& screenshot;
    bool& quit;

    /// Throws InputError "script line N: WHAT".
    [[noreturn]] void fail(const std::string& what) const;
    /// Fails with the render's error if it failed: a wait would not see what it waits for.
    void render_failed() const;
    /// The argument as `yes` (true) or `no` (false); fails for another word.
    bool choice(const char* yes, const char* no) const;
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
    friend std::span<const ScriptVerb> script_verbs();
    /// The verbs and their steps (script_verbs()), which use the runner's state.
    static std::span<const ScriptVerb> verbs();

    /// True while `done` is false (the step ends there); fails the command once the timeout has
    /// passed since the wait began.
    bool waiting(bool done, const ScriptCommand& command, const std::string& what);
    /// ScriptNext::again while `done` is false (waiting()), else go_on.
    ScriptNext wait_for(bool done, const ScriptCommand& command, const std::string& what) {
        return waiting(done, command, what) ? ScriptNext::again : ScriptNext::go_on;
    }

    /// save-view, save-linear: asks the viewer for the save, checked in the next step.
    ScriptNext ask_save(ScriptStep& step, ViewerState::Save what);

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
/// `controls`, `analysis`, `timeline` (the layout's regions, {x, y, w, h}; empty when not shown),
/// `panels` (the panel windows as drawn, with `clipped_cells`), `items` (name to rectangle),
/// `tabs_open` and `errors_shown`.
std::string layout_json(const ViewerState& s);

/// What the Statistics tab shows, as JSON (the script's `write-analysis FILE`): `batch` (its
/// name), `method`, `scene`, `width`, `height`, `rays`, `crop` (the batch is the rays of a region
/// of the image) and `detail` (stats_json(): the per-level table and per-ray summary); with a
/// recording of this batch against another recursion, `against`: its preset, rays, crop, detail
/// and the node pairs where the decisions first differ (`differences`). Throws
/// InputError while the batch has no statistics (not recorded, stale or failed: the reason).
std::string analysis_json(const ViewerState& s);

}  // namespace edacrt::app
