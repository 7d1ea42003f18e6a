#include "script_runner.h"

#include <algorithm>
#include <iostream>

#include "util/error.h"
#include "util/output_file.h"
#include "viewer_jobs.h"

namespace edacrt::app {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

void ScriptRunner::step(ViewerState& s, int shown_spp, std::string& screenshot, bool& quit) {
    // The save asked for in the last frame has been made (or failed) by now.
    if (save_line_ > 0 && s.save_requested == ViewerState::Save::none) {
        const int line = std::exchange(save_line_, 0);
        if (!s.save_error.empty())
            throw InputError("script line " + std::to_string(line) + ": " + s.save_error);
    }
    while (next_ < commands_.size()) {
        const ScriptCommand& c = commands_[next_];
        const auto fail = [&](const std::string& what) {
            throw InputError("script line " + std::to_string(c.line) + ": " + what);
        };
        // A render that failed will not reach what a wait waits for.
        const auto render_failed = [&] {
            if (!s.render_error.empty()) fail("the render failed: " + s.render_error);
        };
        const auto choice = [&](const char* yes, const char* no) {
            if (c.args[0] != yes && c.args[0] != no)
                fail("'" + c.verb + "' takes " + yes + " or " + no);
            return c.args[0] == yes;
        };
        if (c.verb == "wait-spp") {
            if (!waiting_) wait_start_ = Clock::now();
            waiting_ = true;
            if (shown_spp < c.numbers[0]) {
                render_failed();
                if (Clock::now() - wait_start_ > std::chrono::minutes(5))
                    fail("timed out waiting for " + c.args[0] + " spp");
                return;
            }
            waiting_ = false;
        } else if (c.verb == "frames") {
            if (frames_left_ < 0) frames_left_ = int(c.numbers[0]);
            if (frames_left_-- > 0) return;
            frames_left_ = -1;
        } else if (c.verb == "set" || c.verb == "orbit") {
            if (c.verb == "set") try {
                    apply_setting(s, c.args[0], c.args[1]);
                } catch (const InputError& e) {
                    fail(e.what());
                }
            else
                s.camera.orbit(float(c.numbers[0]), float(c.numbers[1]));
            ++next_;
            return;  // the next frame submits the change before anything waits on it
        } else if (c.verb == "view") {
            s.view = parse_enum_or_throw(kViews, c.args[0]);
        } else if (c.verb == "tab") {
            std::string name = c.args[0];
            std::replace(name.begin(), name.end(), '_', ' ');
            s.select_tabs.push_back(name);
        } else if (c.verb == "panels") {
            s.panels_hidden = choice("hidden", "shown");
        } else if (c.verb == "analysis") {
            s.analysis_open = choice("open", "closed");
        } else if (c.verb == "help") {
            s.show_help = choice("on", "off");
        } else if (c.verb == "check-layout") {
            std::string report;
            for (const std::string& p : s.layout_problems) report += "\n  " + p;
            if (!report.empty()) fail("layout problems:" + report);
            std::cout << "layout ok: " << s.placements.size() << " panels, image "
                      << s.layout.image.x << " " << s.layout.image.y << " " << s.layout.image.w
                      << " " << s.layout.image.h << "\n";
        } else if (c.verb == "save-view" || c.verb == "save-linear") {
            s.save_path = c.args[0];
            s.save_requested =
                c.verb == "save-view" ? ViewerState::Save::shown : ViewerState::Save::linear;
            s.save_error.clear();
            save_line_ = c.line;
            ++next_;
            return;  // saved in the next frame, one file per frame
        } else if (c.verb == "write-command") {
            try {
                create_parent_folders(c.args[0]);
                write_file(c.args[0], s.command_line + "\n", "command line");
            } catch (const InputError& e) {
                fail(e.what());
            }
        } else if (c.verb == "bookmark") {
            try {
                save_bookmark(s, c.args[0]);
            } catch (const InputError& e) {
                fail(e.what());
            }
        } else if (c.verb == "record") {
            s.analysis_requested = true;
            analysis_asked_ = true;
        } else if (c.verb == "pick") {
            pick_ = glm::vec2(float(c.numbers[0]), float(c.numbers[1]));
            analysis_asked_ = true;
        } else if (c.verb == "wait-analysis") {
            if (analysis_asked_ || s.analysis_running || s.analysis_requested) {
                render_failed();
                analysis_asked_ = s.analysis_running || s.analysis_requested;
                return;
            }
        } else if (c.verb == "compare") {
            s.compare_requested = true;
            compare_asked_ = true;
            ++next_;
            return;  // started in the next frame
        } else if (c.verb == "wait-compare") {
            if (compare_asked_ || s.comparing || s.compare_requested) {
                render_failed();
                compare_asked_ = s.comparing || s.compare_requested;
                return;
            }
        } else if (c.verb == "wait-played") {
            if (!waiting_) wait_start_ = Clock::now();
            waiting_ = true;
            if (double(s.playback.history.size()) < c.numbers[0]) {
                if (!s.playback.frames) fail("wait-played needs an animated scene");
                render_failed();
                if (!s.playback.playing && !s.playback.error.empty()) fail(s.playback.error);
                if (Clock::now() - wait_start_ > std::chrono::minutes(5))
                    fail("timed out waiting for " + c.args[0] + " played frames");
                return;
            }
            waiting_ = false;
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

}  // namespace edacrt::app
