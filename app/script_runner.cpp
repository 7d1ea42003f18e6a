#include "script_runner.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "trace/stats_json.h"
#include "util/error.h"
#include "util/output_file.h"
#include "util/printable.h"
#include "viewer_jobs.h"

namespace edacrt::app {
namespace {

using Clock = std::chrono::steady_clock;

nlohmann::json rect_json(const Rect& r) { return {{"x", r.x}, {"y", r.y}, {"w", r.w}, {"h", r.h}}; }

/// What wait-settled compares from frame to frame: the regions, the panels as drawn (with their
/// table cells' widths and clipping), the reported widgets and the open tabs.
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

/// A drag of the script's DX, DY pixels (OrbitCamera::orbit or look): a refusal shows on the
/// status line, as a drag shows it, and fails the script.
ScriptNext drag_camera(ScriptStep& st, void (OrbitCamera::*drag)(float, float)) {
    try {
        (st.s.camera.*drag)(float(st.c.numbers[0]), float(st.c.numbers[1]));
    } catch (const InputError& e) {
        st.s.status = e.what();
        st.fail(e.what());
    }
    return ScriptNext::next_frame;
}

/// Writes the text `make` gives for the state to the verb's FILE (the output `what` of
/// check_output_spares_inputs(), `description` in errors); a failure fails the script.
ScriptNext write_output(ScriptStep& st, const char* what, const char* description,
                        std::string (*make)(const ViewerState&)) {
    const std::string& path = st.c.args[0];
    try {
        check_output_spares_inputs(st.s, path, what);
        create_parent_folders(path);
        write_file(path, make(st.s), description);
    } catch (const InputError& e) {
        st.fail(e.what());
    }
    return ScriptNext::go_on;
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

std::string analysis_json(const ViewerState& s) {
    const ShownBatch batch = shown_batch(s);
    const std::string name = batch_name(s.batch);
    if (!batch.detail) {
        const Analysis* a = s.analysis.get();
        if (s.batch != BatchId{} && a && a->batch == s.batch && !a->error.empty())
            throw InputError("no statistics of batch " + name + ": " + a->error);
        throw InputError("no statistics of batch " + name + " yet" +
                         (s.batch == BatchId{} ? std::string(" (wait-spp 1 first)")
                                               : std::string(" (wait-analysis first)")));
    }
    const bool crop = s.batch != BatchId{} && s.analysis->cropped();
    nlohmann::json json = {{"batch", name},
                           {"method", enum_name(kMethods, s.submitted.method)},
                           {"scene", s.scene ? s.scene->source : ""},
                           {"width", batch.width},
                           {"height", batch.height},
                           {"rays", batch.rays},
                           {"crop", crop},
                           {"detail", stats_json(*batch.detail)}};
    // The recording against another recursion (Recursion tab), when it is of this batch.
    if (const Analysis* a = s.analysis.get();
        a && a->against_detail && !s.analysis_stale && a->batch == s.batch) {
        nlohmann::json differences = nlohmann::json::array();
        for (const DecisionDifference& d : a->differences)
            differences.push_back(
                {{"node_a", d.node_a}, {"node_b", d.node_b}, {"depth", d.depth}, {"what", d.what}});
        json["against"] = {{"preset", a->against},
                           {"rays", a->against_detail->rays.size()},
                           {"crop", a->cropped()},
                           {"detail", stats_json(*a->against_detail)},
                           {"differences", differences}};
    }
    return json_text(json);
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

void ScriptStep::fail(const std::string& what) const {
    throw InputError("script line " + std::to_string(c.line) + ": " + what);
}

void ScriptStep::render_failed() const {
    if (!s.render_error.empty()) fail("the render failed: " + s.render_error);
}

bool ScriptStep::choice(const char* yes, const char* no) const {
    if (c.args[0] != yes && c.args[0] != no) fail("'" + c.verb + "' takes " + yes + " or " + no);
    return c.args[0] == yes;
}

std::span<const ScriptVerb> script_verbs() { return ScriptRunner::verbs(); }

std::span<const ScriptVerb> ScriptRunner::verbs() {
    using R = ScriptRunner;
    using Step = ScriptStep;
    using Next = ScriptNext;
    using Args = ScriptArgs;
    static const ScriptVerb kVerbs[] = {
        {"set", 2, Args::words, "KEY VALUE",
         "a setting (app/settings_table.h: method, spp, max-depth, exposure, "
         "compare-spp, ...; "
         "the animation's time, play, speed, loop, update, shutter, play-scale), "
         "an EDACRT flag "
         "without \"--\" (set filter-skip off), preset NAME, scene PATH, animate "
         "SPEC, or the "
         "explorer's level, node, crop (0|1), region (U0,V0,U1,V1|centre) and step, the "
         "analysed batch (batch camera|bounce:N|"
         "shadow:N|ao)",
         [](R&, Step& st) {
             try {
                 apply_setting(st.s, st.c.args[0], st.c.args[1]);
             } catch (const InputError& e) {
                 st.fail(e.what());
             }
             return Next::next_frame;  // the next frame submits the change
         }},
        {"view", 1, Args::words, "NAME", "render | box | triangle | depth | order",
         [](R&, Step& st) {
             st.s.view = parse_enum_or_throw(kViews, st.c.args[0]);
             return Next::next_frame;  // what a wait sees comes after the change is
                                       // drawn
         }},
        {"tab", 1, Args::words, "NAME", "bring a tab forward (NAME with '_' for spaces: Heat_map)",
         [](R&, Step& st) {
             std::string name = st.c.args[0];
             std::replace(name.begin(), name.end(), '_', ' ');
             st.s.select_tabs.push_back(name);
             return Next::next_frame;
         }},
        {"panels", 1, Args::words, "hidden|shown", "hide all panels (Tab) or show them",
         [](R&, Step& st) {
             st.s.panels_hidden = st.choice("hidden", "shown");
             return Next::next_frame;
         }},
        {"analysis", 1, Args::words, "open|closed", "expand or collapse the analysis area",
         [](R&, Step& st) {
             st.s.analysis_open = st.choice("open", "closed");
             return Next::next_frame;
         }},
        {"help", 1, Args::words, "on|off", "the help overlay",
         [](R&, Step& st) {
             st.s.show_help = st.choice("on", "off");
             return Next::next_frame;
         }},
        {"orbit", 2, Args::real, "DX DY", "drag the camera by DX, DY pixels",
         [](R&, Step& st) { return drag_camera(st, &OrbitCamera::orbit); }},
        {"look", 2, Args::real, "DX DY",
         "turn the view about the eye as a right drag of DX, DY pixels does",
         [](R&, Step& st) { return drag_camera(st, &OrbitCamera::look); }},
        {"orbit-about", 2, Args::fraction, "U V",
         "orbit about the surface point at fractions U, V of the image (a double click)",
         [](R&, Step& st) {
             if (!orbit_about_pixel(st.s, float(st.c.numbers[0]), float(st.c.numbers[1])))
                 st.fail(st.s.status);
             return Next::next_frame;
         }},
        {"wait-spp", 1, Args::count, "N",
         "until the shown image has N samples per pixel (of the current "
         "settings)",
         [](R& r, Step& st) {
             if (st.shown.spp < st.c.numbers[0]) st.render_failed();
             return r.wait_for(st.shown.spp >= st.c.numbers[0], st.c, st.c.args[0] + " spp");
         }},
        {"wait-loaded", 0, Args::words, "",
         "until the scenes asked for (set scene) are loaded and the render asked "
         "for has begun "
         "(its first frame or its error); fails the script with the error when "
         "the last load "
         "or that render failed",
         [](R& r, Step& st) {
             // A scene is read on a thread of its own and taken at the start of a frame; the
             // render of the scene is asked for after the panels are drawn.
             const ViewerState& s = st.s;
             const bool tried = s.pending_loads.empty() && !s.loading;
             if (tried && !s.scene_error.empty())
                 st.fail("the scene did not load: " + s.scene_error);
             // Loaded means the tracer took it too: a method that refuses the scene (Embree past
             // its range) fails here as the other waits fail, not at the next wait.
             const bool submitted = tried && s.scene && s.submitted.scene == s.scene;
             if (submitted) st.render_failed();
             return r.wait_for(submitted && s.render_answered, st.c, "the scene to load");
         }},
        {"wait-error", 0, Args::words, "",
         "until an error message is on screen (drawn by the panels in the last "
         "frame; with the "
         "panels hidden, one they would show: scene, resolution, render or "
         "animation) and "
         "prints it (\"error shown: ...\")",
         [](R& r, Step& st) {
             const ViewerState& s = st.s;
             std::string error;
             if (!s.errors_shown.empty()) error = s.errors_shown.front();
             if (s.panels_hidden)
                 for (const std::string* e :
                      {&s.scene_error, &s.resolution_error, &s.render_error, &s.playback.error})
                     if (error.empty()) error = *e;
             if (r.waiting(!error.empty(), st.c, "an error message on screen")) return Next::again;
             std::cout << "error shown: " << printable(error) << "\n";
             return Next::go_on;
         }},
        {"wait-settled", 0, Args::words, "",
         "until the screen shows what was asked: the view of the current "
         "render's latest "
         "full-resolution pass, the tabs brought forward, and the panels, "
         "widgets and table "
         "columns unchanged for three frames",
         [](R& r, Step& st) {
             const bool asked =
                 st.s.select_tabs.empty() && st.s.pending_loads.empty() && !st.s.loading;
             if (!st.shown.image_current) st.render_failed();
             return r.wait_for(asked && st.shown.image_current && r.same_layout_frames_ >= 2, st.c,
                               "the screen to settle (the view asked for of the current render, "
                               "the tabs asked for, the layout unchanged for three frames)");
         }},
        {"timeout", 1, Args::seconds, "S",
         "the waits that follow fail the script after S seconds (default 300)",
         [](R& r, Step& st) {
             r.timeout_ = std::chrono::duration<double>(st.c.numbers[0]);
             return Next::go_on;
         }},
        {"frames", 1, Args::count, "N",
         "let N frames pass (demos; tests wait for a condition instead)",
         [](R& r, Step& st) {
             if (r.frames_left_ < 0) r.frames_left_ = int(st.c.numbers[0]);
             if (r.frames_left_-- > 0) return Next::again;
             r.frames_left_ = -1;
             return Next::go_on;
         }},
        {"check-layout", 0, Args::words, "",
         "fail unless every panel is inside the window, off the image region, "
         "with no table "
         "cell clipped (the last frame's layout)",
         [](R&, Step& st) {
             const ViewerState& s = st.s;
             std::string report;
             for (const std::string& p : s.layout_problems) report += "\n  " + p;
             if (!report.empty()) st.fail("layout problems:" + report);
             std::cout << "layout ok: " << s.placements.size() << " panels, image "
                       << s.layout.image.x << " " << s.layout.image.y << " " << s.layout.image.w
                       << " " << s.layout.image.h << "\n";
             return Next::go_on;
         }},
        {"layout", 1, Args::words, "FILE",
         "write the last frame's layout as JSON (layout_json()): the window, the "
         "image region, "
         "the panels and the widgets the panels report, in window coordinates "
         "(times "
         "framebuffer_scale for screenshot pixels)",
         [](R&, Step& st) { return write_output(st, "layout", "layout", layout_json); }},
        {"save-view", 1, Args::words, "FILE", "save the image region as shown (.png or .jpg)",
         [](R& r, Step& st) { return r.ask_save(st, ViewerState::Save::shown); }},
        {"save-linear", 1, Args::words, "FILE",
         "save the render (.exr, .pfm, .hdr linear; .png, .jpg tone-mapped)",
         [](R& r, Step& st) { return r.ask_save(st, ViewerState::Save::linear); }},
        {"write-command", 1, Args::words, "FILE",
         "write the `edacrt render` command that reproduces the view",
         [](R&, Step& st) {
             return write_output(st, "write-command", "command line",
                                 [](const ViewerState& s) { return s.command_line + "\n"; });
         }},
        {"write-analysis", 1, Args::words, "FILE",
         "write what Statistics shows as JSON: the batch (`set batch camera|bounce:N|shadow:N|"
         "ao`), its ray count and the per-level table (after wait-analysis for a batch other "
         "than the camera rays)",
         [](R&, Step& st) {
             return write_output(st, "write-analysis", "analysis", analysis_json);
         }},
        {"bookmark", 1, Args::words, "NAME",
         "save the view as the scene's bookmark NAME in the bookmarks file "
         "(--bookmarks), as "
         "the Camera tab's \"save view\" does",
         [](R&, Step& st) {
             try {
                 save_bookmark(st.s, st.c.args[0]);
             } catch (const InputError& e) {
                 st.fail(e.what());
             }
             return Next::go_on;
         }},
        {"record", 0, Args::words, "", "record the view's recursion (recursion explorer)",
         [](R& r, Step& st) {
             st.s.analysis_requested = true;
             r.analysis_asked_ = true;
             return Next::go_on;
         }},
        {"pick", 2, Args::real, "X Y",
         "follow the camera ray under window position X, Y (traversal debugger)",
         [](R& r, Step& st) {
             r.pick_ = glm::vec2(float(st.c.numbers[0]), float(st.c.numbers[1]));
             r.analysis_asked_ = true;
             return Next::go_on;
         }},
        {"pick-image", 2, Args::fraction, "U V",
         "the same at fractions U, V (0 to 1) of the image region's width, "
         "height",
         [](R& r, Step& st) {
             // Inside the region: its right and bottom edges belong to no pixel.
             const Rect& image = st.s.layout.image;
             if (image.empty()) st.fail("there is no image region to pick in");
             r.pick_ =
                 glm::vec2(image.x + std::min(float(st.c.numbers[0]) * image.w, image.w - 0.5f),
                           image.y + std::min(float(st.c.numbers[1]) * image.h, image.h - 0.5f));
             r.analysis_asked_ = true;
             return Next::go_on;
         }},
        {"wait-analysis", 0, Args::words, "", "until the recording or the followed ray is ready",
         [](R& r, Step& st) {
             // Asked for in this step, the analysis starts in the next frame: one more step.
             const bool busy =
                 r.analysis_asked_ || st.s.analysis_running || st.s.analysis_requested;
             if (busy) st.render_failed();
             r.analysis_asked_ = st.s.analysis_running || st.s.analysis_requested;
             return r.wait_for(!busy, st.c, "the analysis");
         }},
        {"compare", 0, Args::words, "", "time every method on the view (Statistics, Frames)",
         [](R& r, Step& st) {
             st.s.compare_requested = true;
             r.compare_asked_ = true;
             return Next::next_frame;  // started in the next frame
         }},
        {"wait-compare", 0, Args::words, "", "until the comparison is done",
         [](R& r, Step& st) {
             const bool busy = r.compare_asked_ || st.s.comparing || st.s.compare_requested;
             if (busy) st.render_failed();
             r.compare_asked_ = st.s.comparing || st.s.compare_requested;
             return r.wait_for(!busy, st.c, "the comparison");
         }},
        {"wait-played", 1, Args::count, "N",
         "until N frames of the animation were rendered since it was loaded (set "
         "play 1 first; "
         "set time T shows time T, paused)",
         [](R& r, Step& st) {
             const Playback& p = st.s.playback;
             const bool played = double(p.history.size()) >= st.c.numbers[0];
             if (!played) {
                 if (!p.frames) st.fail("wait-played needs an animated scene");
                 st.render_failed();
                 if (!p.playing && !p.error.empty()) st.fail(p.error);
             }
             return r.wait_for(played, st.c, st.c.args[0] + " played frames");
         }},
        {"screenshot", 1, Args::words, "FILE", "save the window as PNG",
         [](R&, Step& st) {
             st.screenshot = st.c.args[0];
             return Next::next_frame;  // taken at the end of this frame
         }},
        {"quit", 0, Args::words, "", "quit",
         [](R&, Step& st) {
             st.quit = true;
             return Next::go_on;
         }},
    };
    return kVerbs;
}

ScriptNext ScriptRunner::ask_save(ScriptStep& st, ViewerState::Save what) {
    st.s.save_path = st.c.args[0];
    st.s.save_requested = what;
    st.s.save_error.clear();
    save_line_ = st.c.line;
    return ScriptNext::next_frame;  // saved in the next frame, one file per frame
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
        ScriptStep st{s, shown, c, screenshot, quit};
        const ScriptVerb* verb = nullptr;
        for (const ScriptVerb& v : verbs())
            if (v.name == c.verb) verb = &v;
        if (!verb) st.fail("unknown script command '" + c.verb + "'");  // parse_script's
        const ScriptNext next = verb->run(*this, st);
        if (next == ScriptNext::again) return;
        ++next_;
        if (next == ScriptNext::next_frame) return;
    }
}

}  // namespace edacrt::app
