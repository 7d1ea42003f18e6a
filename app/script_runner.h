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

/// Runs the script one step per frame; step() throws InputError naming the line that failed.
class ScriptRunner {
  public:
    explicit ScriptRunner(std::vector<ScriptCommand> commands) : commands_(std::move(commands)) {}

    /// Commands are left, or a save whose outcome the script has not checked yet.
    bool active() const { return next_ < commands_.size() || save_line_ > 0; }

    /// `shown_spp`: samples of the current request on screen (0 while a preview is shown).
    void step(ViewerState& s, int shown_spp, std::string& screenshot, bool& quit);

    /// A window position to pick (the traversal debugger), consumed by the viewer.
    std::optional<glm::vec2> take_pick() { return std::exchange(pick_, std::nullopt); }

  private:
    std::vector<ScriptCommand> commands_;
    std::optional<glm::vec2> pick_;
    bool analysis_asked_ = false;
    bool compare_asked_ = false;
    std::size_t next_ = 0;
    int save_line_ = 0;  // the line of a save asked for and not checked yet
    int frames_left_ = -1;
    bool waiting_ = false;
    std::chrono::steady_clock::time_point wait_start_;
};

}  // namespace edacrt::app
