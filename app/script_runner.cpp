#include "script_runner.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "util/error.h"
#include "util/output_file.h"
#include "util/printable.h"
#include "viewer_jobs.h"

namespace edacrt::app {
namespace {

using Clock = std::chrono::steady_clock;

nlohmann::json rect_json(const Rect& r) { return {{"x", r.x}, {"y", r.y}, {"w", r.w}, {"h", r.h}}; }

/// What wait-settled compares from frame to frame: the regions, the panels as drawn (with
/// their table cells' widths and clipping), the reported widgets and the open tabs.
std::string layout_signature(const ViewerState& s) {
    std::string text;
    char buffer[160];
    const auto add_rect = [&](const std::string& name, const Rect& r) {
        std::snprintf(buffer, sizeof buffer, "|%g %g %g %g ", r.x, r.y, r.w, r.h);
        text += name + buffer;
    };
    add_rect("image", s.layout.image);
    for (const PanelPlacement& p : s.placements) {
        add_rect(p.name, p.rect);
        text += std::to_string(p.clipped_cells) + " " + std::to_string(p.cell_widths);
    }
    for (const NamedRect& item : s.items) add_rect(item.name, item.rect);
    for (const std::string& tab : s.tabs_open) text += "|tab " + tab;
    return text;
}

std::string seconds_text(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", seconds);
    return text;
}

}  // namespace

std::string layout_json(const ViewerState& s) {
    nlohmann::json panels = nlohmann::json::object(), items = nlohmann::json::object();
    for (const PanelPlacement& p : s.placements) {
        panels[p.name] = rect_json(p.rect);
        panels[p.name]["clipped_cells"] = p.clipped_cells;
    }
    for (const NamedRect& item : s.items) items[item.name] = rect_json(item.rect);
    const nlohmann::json json = {
        {"window", {{"w", s.window_width}, {"h", s.window_height}}},
        {"framebuffer_scale", {{"x", s.framebuffer_scale_x}, {"y", s.framebuffer_scale_y}}},
        {"image", rect_json(s.layout.image)},
        {"controls", rect_json(s.layout.controls)},
        {"analysis", rect_json(s.layout.analysis)},
        {"timeline", rect_json(s.layout.timeline)},
        {"panels", panels},
        {"items", items},
        {"tabs_open", s.tabs_open},
        {"errors_shown", s.errors_shown}};
    return json.dump(2) + "\n";
}

bool ScriptRunner::waiting(bool done, const ScriptCommand& c, const std::string& what) {
    if (done) {
        waiting_ = false;
        return false;
    }
    const auto now = Clock::now();
    if (!waiting_) wait_start_ = now;
    waiting_ = true;
    if (now - wait_start_ > timeout_) {
        waiting_ = false;
        throw InputError("script line " + std::to_string(c.line) + ": timed out after " +
                         seconds_text(timeout_.count()) + " s waiting for " + what);
    }
    return true;
}

void ScriptRunner::step(ViewerState& s, const ShownFrame& shown, std::string& screenshot,
                        bool& quit) {
    // The layout drawn this frame against the last one, whatever the script is doing.
    std::string layout = layout_signature(s);
    same_layout_frames_ = layout == last_layout_ ? same_layout_frames_ + 1 : 0;
    last_layout_ = std::move(layout);
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
            if (shown.spp < c.numbers[0]) render_failed();
            if (waiting(shown.spp >= c.numbers[0], c, c.args[0] + " spp")) return;
        } else if (c.verb == "wait-loaded") {
            // A load is made at the start of a frame; the render of the scene is asked for
            // after the panels are drawn.
            const bool tried = s.pending_loads.empty();
            if (tried && !s.scene_error.empty()) fail("the scene did not load: " + s.scene_error);
            // Loaded means the tracer took it too: a method that refuses the scene (Embree past
            // its range) fails here as the other waits fail, not at the next wait.
            const bool submitted = tried && s.scene && s.submitted.scene == s.scene;
            if (submitted) render_failed();
            if (waiting(submitted && s.render_answered, c, "the scene to load")) return;
        } else if (c.verb == "wait-error") {
            std::string error;
            if (!s.errors_shown.empty()) error = s.errors_shown.front();
            if (s.panels_hidden)
                for (const std::string* e :
                     {&s.scene_error, &s.resolution_error, &s.render_error, &s.playback.error})
                    if (error.empty()) error = *e;
            if (waiting(!error.empty(), c, "an error message on screen")) return;
            std::cout << "error shown: " << printable(error) << "\n";
        } else if (c.verb == "wait-settled") {
            const bool asked = s.select_tabs.empty() && s.pending_loads.empty();
            if (!shown.image_current) render_failed();
            if (waiting(asked && shown.image_current && same_layout_frames_ >= 2, c,
                        "the screen to settle (the view asked for of the current render, the "
                        "tabs asked for, the layout unchanged for three frames)"))
                return;
        } else if (c.verb == "timeout") {
            timeout_ = std::chrono::duration<double>(c.numbers[0]);
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
                try {
                    s.camera.orbit(float(c.numbers[0]), float(c.numbers[1]));
                } catch (const InputError& e) {
                    s.status = e.what();  // as a drag shows it
                    fail(e.what());
                }
            ++next_;
            return;  // the next frame submits the change before anything waits on it
        } else if (c.verb == "view" || c.verb == "tab" || c.verb == "panels" ||
                   c.verb == "analysis" || c.verb == "help") {
            if (c.verb == "view") {
                s.view = parse_enum_or_throw(kViews, c.args[0]);
            } else if (c.verb == "tab") {
                std::string name = c.args[0];
                std::replace(name.begin(), name.end(), '_', ' ');
                s.select_tabs.push_back(name);
            } else if (c.verb == "panels") {
                s.panels_hidden = choice("hidden", "shown");
            } else if (c.verb == "analysis") {
                s.analysis_open = choice("open", "closed");
            } else {
                s.show_help = choice("on", "off");
            }
            ++next_;
            return;  // the next frame draws the change: what a wait sees comes after it
        } else if (c.verb == "check-layout") {
            std::string report;
            for (const std::string& p : s.layout_problems) report += "\n  " + p;
            if (!report.empty()) fail("layout problems:" + report);
            std::cout << "layout ok: " << s.placements.size() << " panels, image "
                      << s.layout.image.x << " " << s.layout.image.y << " " << s.layout.image.w
                      << " " << s.layout.image.h << "\n";
        } else if (c.verb == "layout") {
            try {
                check_output_spares_inputs(s, c.args[0], "layout");
                create_parent_folders(c.args[0]);
                write_file(c.args[0], layout_json(s), "layout");
            } catch (const InputError& e) {
                fail(e.what());
            }
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
                check_output_spares_inputs(s, c.args[0], "write-command");
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
        } else if (c.verb == "pick" || c.verb == "pick-image") {
            if (c.verb == "pick") {
                pick_ = glm::vec2(float(c.numbers[0]), float(c.numbers[1]));
            } else {
                // Inside the region: its right and bottom edges belong to no pixel.
                const Rect& r = s.layout.image;
                if (r.empty()) fail("there is no image region to pick in");
                pick_ = glm::vec2(r.x + std::min(float(c.numbers[0]) * r.w, r.w - 0.5f),
                                  r.y + std::min(float(c.numbers[1]) * r.h, r.h - 0.5f));
            }
            analysis_asked_ = true;
        } else if (c.verb == "wait-analysis") {
            // Asked for in this step, the analysis starts in the next frame: one more step.
            const bool busy = analysis_asked_ || s.analysis_running || s.analysis_requested;
            if (busy) render_failed();
            analysis_asked_ = s.analysis_running || s.analysis_requested;
            if (waiting(!busy, c, "the analysis")) return;
        } else if (c.verb == "compare") {
            s.compare_requested = true;
            compare_asked_ = true;
            ++next_;
            return;  // started in the next frame
        } else if (c.verb == "wait-compare") {
            const bool busy = compare_asked_ || s.comparing || s.compare_requested;
            if (busy) render_failed();
            compare_asked_ = s.comparing || s.compare_requested;
            if (waiting(!busy, c, "the comparison")) return;
        } else if (c.verb == "wait-played") {
            const bool played = double(s.playback.history.size()) >= c.numbers[0];
            if (!played) {
                if (!s.playback.frames) fail("wait-played needs an animated scene");
                render_failed();
                if (!s.playback.playing && !s.playback.error.empty()) fail(s.playback.error);
            }
            if (waiting(played, c, c.args[0] + " played frames")) return;
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
