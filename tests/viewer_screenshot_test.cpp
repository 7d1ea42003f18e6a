// The viewer under xvfb-run (Mesa llvmpipe): it starts on the Cornell box, renders, and a
// scripted session saves screenshots of the render, every heat map, and the render after a
// parameter change. The checks look at image regions: the panels are drawn, the walls have
// their colours, the heat maps are heat maps. Scripts wait for the state they check
// (wait-spp, wait-settled, wait-error, wait-loaded: no frame counts), and the regions sampled
// are the ones the viewer's `layout FILE` reports for the frame of the screenshot.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "render/exr_image.h"
#include "render/image.h"
#include "sanitizers.h"
#include "temp_dir.h"
#include "test_paths.h"

namespace edacrt {
namespace {

/// A rectangle of a screenshot, in pixels: [x0, x1) x [y0, y1).
struct Region {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    int area() const { return std::max(x1 - x0, 0) * std::max(y1 - y0, 0); }
    /// The part [u0, u1) x [v0, v1) of it, in fractions of its width and height.
    Region part(double u0, double v0, double u1, double v1) const {
        const auto at = [](int a, int b, double t) { return a + int(std::lround((b - a) * t)); };
        return {at(x0, x1, u0), at(y0, y1, v0), at(x0, x1, u1), at(y0, y1, v1)};
    }
    bool contains(const Region& r) const {
        return r.x0 >= x0 && r.y0 >= y0 && r.x1 <= x1 && r.y1 <= y1;
    }
};

std::ostream& operator<<(std::ostream& out, const Region& r) {
    return out << "[" << r.x0 << ", " << r.x1 << ") x [" << r.y0 << ", " << r.y1 << ")";
}

/// The layout the viewer's `layout FILE` wrote (in the frame of the screenshot that follows
/// it), its rectangles in screenshot pixels.
class ShownLayout {
  public:
    explicit ShownLayout(const std::filesystem::path& file)
        : json_(nlohmann::json::parse(std::ifstream(file))) {}

    Region image() const { return pixels(json_.at("image")); }
    Region panel(const std::string& name) const { return pixels(find("panels", name)); }
    Region item(const std::string& name) const { return pixels(find("items", name)); }
    const nlohmann::json& json() const { return json_; }

  private:
    const nlohmann::json& find(const char* group, const std::string& name) const {
        if (!json_.at(group).contains(name))
            throw std::runtime_error(std::string("the layout has no ") + group + " '" + name +
                                     "': " + json_.dump());
        return json_.at(group).at(name);
    }
    Region pixels(const nlohmann::json& r) const {
        const double sx = json_.at("framebuffer_scale").at("x");
        const double sy = json_.at("framebuffer_scale").at("y");
        const double x = r.at("x"), y = r.at("y"), w = r.at("w"), h = r.at("h");
        return {int(std::lround(x * sx)), int(std::lround(y * sy)), int(std::lround((x + w) * sx)),
                int(std::lround((y + h) * sy))};
    }
    nlohmann::json json_;
};

/// Mean linear colour of the region (NaN when it is empty).
glm::vec3 mean(const Image& image, const Region& r) {
    glm::dvec3 sum(0.0);
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) sum += glm::dvec3(image.at(x, y));
    return glm::vec3(sum / double(r.area()));
}

/// Fraction of pixels in the region whose channels spread by more than 0.15 (coloured).
double coloured(const Image& image, const Region& r) {
    int count = 0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const glm::vec3 c = image.at(x, y);
            count += std::max({c.x, c.y, c.z}) - std::min({c.x, c.y, c.z}) > 0.15f;
        }
    return double(count) / double(r.area());
}

/// Occurrences of `text` in `output`.
std::size_t count(const std::string& output, const std::string& text) {
    std::size_t n = 0;
    for (std::size_t at = 0; (at = output.find(text, at)) != std::string::npos; ++at) ++n;
    return n;
}

bool have_xvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

/// The viewer (with `args`) under a virtual X server of a screen of width x height. In
/// sanitizer builds leak checking is off for this process only: Mesa's driver (dlopen'ed,
/// unloaded at exit) leaks a few hundred bytes that LeakSanitizer cannot attribute. The
/// viewer's own parts are leak-checked in edacrt_viewer_core_tests.
///
/// -noreset: without it Xvfb resets when its last client (the viewer) disconnects and signals
/// xvfb-run (SIGUSR1, its "ready" signal) again. That signal can arrive while xvfb-run's exit
/// trap removes its temporary folder, and dash (Debian's /bin/sh, 0.5.12) then sets `$?` to
/// the exit status the script is leaving with: after a viewer that exited 1, the successful
/// `rm` reads as failed and xvfb-run exits 5 ("problem while cleaning up temporary
/// directory") instead of 1, by chance.
std::string xvfb_viewer(int screen_width, int screen_height, const std::string& args) {
    return "ASAN_OPTIONS=detect_leaks=0 xvfb-run -a -s '-screen 0 " + std::to_string(screen_width) +
           "x" + std::to_string(screen_height) + "x24 -noreset' " EDACRT_VIEWER " " + args;
}

/// Under the sanitizers rendering dominates a screenshot test (the Cornell box's 4 samples per
/// pixel at 1280x800: 31 s with ASan, 9 s at half resolution), so the tests whose point is not
/// the render's size render at half the image region's size there.
const std::string kSanitizedResolution = test::kSanitized ? "--resolution 0.5 " : "";

/// The viewer in a 1280x800 window filling the virtual screen.
std::string viewer_under_xvfb(const std::string& args) {
    return xvfb_viewer(1280, 800, "--width 1280 --height 800 " + args);
}

// Before any window: a script that is a FIFO or a directory is refused, not waited on (no
// X server needed).
TEST(ViewerScreenshots, AScriptThatIsNotARegularFileIsRefusedAtOnce) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("edacrt_viewer_script_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    ASSERT_EQ(::mkfifo((dir / "fifo.txt").c_str(), 0600), 0);
    for (const auto& script : {dir / "fifo.txt", dir}) {
        const auto result =
            test::run_command("timeout 20 " EDACRT_VIEWER " --script " + script.string());
        EXPECT_EQ(result.exit_code, 1) << result.output;
        EXPECT_NE(
            result.output.find("edacrt_viewer: error: " + script.string() + ": not a regular file"),
            std::string::npos)
            << result.output;
    }
    std::filesystem::remove_all(dir);
}

TEST(ViewerScreenshots, CornellBoxRenderHeatMapsAndParameterChange) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const auto dir =
        std::filesystem::temp_directory_path() / ("edacrt_viewer_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto shot = [&](const std::string& name) { return (dir / (name + ".png")).string(); };
    const auto layout = [&](const std::string& name) { return (dir / (name + ".json")); };
    // Each screenshot with the layout of its frame.
    const auto take = [&](const std::string& name) {
        return "layout " + layout(name).string() + "\nscreenshot " + shot(name) + "\n";
    };
    // The panels hidden: the image fills the window (the layout is tested below). The broken
    // scene's error is waited for hidden (held for the panel), then drawn in the Scene tab.
    std::ofstream(dir / "script.txt")
        << "panels hidden\nwait-spp 4\n"
        << take("render") << "view box\nwait-settled\n"
        << take("box") << "view triangle\nwait-settled\n"
        << take("triangle") << "view depth\nwait-settled\n"
        << take("depth") << "view order\nwait-settled\n"
        << take("order")
        << "view render\nset method bvh\nset bins 16\nset integrator ao\nwait-spp 2\n"
        << take("changed") << "set scene /no/such/scene.obj\nwait-error\nwait-settled\n"
        << take("after_bad_scene") << "panels shown\nwait-error\nwait-settled\ncheck-layout\n"
        << take("panels");
    const std::string scene =
        (test::source_dir() / "assets/cornell-box/CornellBox-Original.obj").string();
    const auto result = test::run_command(viewer_under_xvfb(
        kSanitizedResolution + "--script " + (dir / "script.txt").string() + " " + scene));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(count(result.output, "error shown: /no/such/scene.obj"), 2u) << result.output;

    const Image render = read_png(shot("render"));
    ASSERT_EQ(render.width, 1280);
    ASSERT_EQ(render.height, 800);
    // The render: the red left wall, the green right wall, a lit back wall (where they are in
    // the image region: here the whole window).
    const Region image = ShownLayout(layout("render")).image();
    EXPECT_EQ(image.area(), 1280 * 800) << image;
    const Region left_wall = image.part(0.297, 0.3125, 0.344, 0.5),
                 right_wall = image.part(0.656, 0.25, 0.703, 0.475),
                 back_wall = image.part(0.4375, 0.275, 0.5625, 0.375);
    const glm::vec3 left = mean(render, left_wall), right = mean(render, right_wall);
    EXPECT_GT(left.x, 2.0f * left.y) << "red wall";
    EXPECT_GT(right.y, 1.5f * right.x) << "green wall";
    EXPECT_GT(mean(render, back_wall).x, 0.02f) << "back wall lit";

    // The panels: the Scene tab's widgets (blue frames and buttons, white text) where the
    // layout says, its header one line whatever the checkout's path (it names the file only),
    // the broken scene's error in red.
    const ShownLayout panels(layout("panels"));
    const Image shown = read_png(shot("panels"));
    const Region controls = panels.panel("Controls");
    // The help button: visible in the tab bar without looking for it.
    for (const char* name :
         {"Scene/label", "Scene/scenes", "Scene/load", "Scene/error", "Controls/help"})
        EXPECT_TRUE(controls.contains(panels.item(name))) << name << " " << panels.item(name);
    const Region label = panels.item("Scene/label"), list = panels.item("Scene/scenes");
    EXPECT_LT(label.y1 - label.y0, list.y1 - list.y0) << "the header wraps: " << label;
    if (panels.json()["items"].contains("Scene/hint")) {  // some public scenes not fetched
        const Region hint = panels.item("Scene/hint");    // the scenes folder is its tooltip
        EXPECT_LE(hint.y1 - hint.y0, 2 * (label.y1 - label.y0)) << "the hint wraps: " << hint;
    }
    EXPECT_FALSE(panels.image().contains(list));
    for (const char* name : {"Scene/scenes", "Scene/load"}) {
        const glm::vec3 widgets = mean(shown, panels.item(name));
        EXPECT_GT(widgets.z, 1.5f * widgets.x) << "ImGui widgets: " << name;
        EXPECT_GT(widgets.z, 0.05f) << "ImGui widgets: " << name;
    }
    const glm::vec3 error = mean(shown, panels.item("Scene/error"));
    EXPECT_GT(error.x, 2.0f * error.z) << "the error in red";
    EXPECT_GT(error.x, 0.05f) << "the error in red";

    for (const char* heat : {"box", "triangle", "depth", "order"}) {
        const Image map = read_png(shot(heat));
        const Region back = ShownLayout(layout(heat)).image().part(0.4375, 0.275, 0.5625, 0.375);
        // The box interior shows the colour ramp, not the render (few order misses here: the
        // ramp's dark end, so only the difference is checked for that one).
        if (std::string(heat) != "order") {
            EXPECT_GT(coloured(map, back), 0.9) << heat;
        }
        const glm::vec3 d = mean(map, back) - mean(render, back_wall);
        EXPECT_GT(glm::length(d), 0.05f) << heat;
    }
    // Ambient occlusion: the red wall's albedo times its open sky, not the path tracer's light.
    const Image changed = read_png(shot("changed"));
    const Region changed_wall =
        ShownLayout(layout("changed")).image().part(0.297, 0.3125, 0.344, 0.5);
    const glm::vec3 wall = mean(changed, changed_wall);
    EXPECT_GT(wall.x, 2.0f * wall.y) << "ao shows the red albedo";
    EXPECT_GT(glm::length(wall - left), 0.05f) << "ao, not the path tracer's image";
    // A broken scene file leaves the current scene on screen (its error shows in the panel).
    const Image after = read_png(shot("after_bad_scene"));
    const Region after_wall =
        ShownLayout(layout("after_bad_scene")).image().part(0.297, 0.3125, 0.344, 0.5);
    EXPECT_LT(glm::length(mean(after, after_wall) - wall), 0.02f);
    if (!HasFailure()) std::filesystem::remove_all(dir);  // kept for a look otherwise
}

/// Fraction of pixels in the region close to the colour c (8-bit sRGB).
double near_colour(const Image& image, const Region& r, glm::vec3 srgb) {
    int count = 0;
    const auto linear = [](float c) {
        return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    };
    const glm::vec3 target(linear(srgb.x), linear(srgb.y), linear(srgb.z));
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) count += glm::length(image.at(x, y) - target) < 0.08f;
    return double(count) / double(r.area());
}

TEST(ViewerScreenshots, RecursionExplorerAndTraversalDebuggerDrawTheirBoxes) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const auto dir = std::filesystem::temp_directory_path() /
                     ("edacrt_viewer_debug_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto shot = [&](const std::string& name) { return (dir / (name + ".png")).string(); };
    const auto take = [&](const std::string& name) {
        return "layout " + (dir / (name + ".json")).string() + "\nscreenshot " + shot(name) + "\n";
    };
    const auto image = [&](const std::string& name) {
        return ShownLayout(dir / (name + ".json")).image();
    };
    // The teapot: enough triangles for a few levels. The debugger follows the middle pixel of
    // the image region.
    std::ofstream(dir / "script.txt")
        << "wait-spp 1\nwait-settled\n"
        << take("plain") << "tab Traversal\npick-image 0.5 0.5\nwait-analysis\nwait-settled\n"
        << take("debugger") << "orbit 60 0\nwait-settled\n"
        << take("moved");
    const std::string scene = (test::source_dir() / "assets/teapot/teapot.obj").string();
    const auto result = test::run_command(
        viewer_under_xvfb(kSanitizedResolution + "--integrator primary --script " +
                          (dir / "script.txt").string() + " " + scene));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const Image plain = read_png(shot("plain")), debugger = read_png(shot("debugger"));
    // The followed ray's boxes: yellow (255, 230, 60) lines appear over the image region.
    const glm::vec3 yellow(1.0f, 230.0f / 255.0f, 60.0f / 255.0f);
    EXPECT_EQ(near_colour(plain, image("plain"), yellow), 0.0);
    EXPECT_GT(near_colour(debugger, image("debugger"), yellow), 1e-4);
    // The camera moved: the recording is stale and its boxes are no longer drawn.
    EXPECT_EQ(near_colour(read_png(shot("moved")), image("moved"), yellow), 0.0);
    if (!HasFailure()) std::filesystem::remove_all(dir);
}

// The EDACRT panel with the defaults greys C_T (no cost leaf) and C_child (filter skipping by
// the paper's rule); a cost leaf above leaf-tris brings C_T back. The same widget, at the same
// value, is compared in both frames: only its greying differs.
TEST(ViewerScreenshots, AParameterWithoutEffectIsGreyed) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const auto dir = std::filesystem::temp_directory_path() /
                     ("edacrt_viewer_params_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto shot = [&](const std::string& name) { return (dir / (name + ".png")).string(); };
    const auto take = [&](const std::string& name) {
        return "layout " + (dir / (name + ".json")).string() + "\nscreenshot " + shot(name) + "\n";
    };
    std::ofstream(dir / "script.txt")
        << "wait-loaded\ntab EDACRT\nwait-settled\n"
        << take("defaults") << "set cost-leaf-max-tris 64\nwait-settled\n"
        << take("cost_leaf");
    const std::string scene =
        (test::source_dir() / "assets/cornell-box/CornellBox-Original.obj").string();
    const auto result = test::run_command(
        viewer_under_xvfb("--script " + (dir / "script.txt").string() + " " + scene));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const ShownLayout before(dir / "defaults.json"), after(dir / "cost_leaf.json");
    const Image greyed = read_png(shot("defaults")), live = read_png(shot("cost_leaf"));
    // Brightness of a widget (frame, slider grab, label): greyed, ImGui draws it at 60% alpha.
    const auto shown = [](const Image& image, const Region& r) {
        const glm::vec3 c = mean(image, r);
        return c.x + c.y + c.z;
    };
    const float c_t_greyed = shown(greyed, before.item("EDACRT/c-t"));
    const float c_t_live = shown(live, after.item("EDACRT/c-t"));
    EXPECT_LT(c_t_greyed, 0.8f * c_t_live) << c_t_greyed << " " << c_t_live;
    // C_child stays greyed, C_I live, in both frames.
    for (const auto& [image, layout] : {std::pair(&greyed, &before), std::pair(&live, &after)}) {
        const float c_i = shown(*image, layout->item("EDACRT/c-i"));
        EXPECT_LT(shown(*image, layout->item("EDACRT/c-child")), 0.8f * c_i);
        EXPECT_NEAR(c_i, c_t_live, 0.2f * c_t_live) << "live sliders look alike";
    }
    if (!HasFailure()) std::filesystem::remove_all(dir);
}

TEST(ViewerScreenshots, AResolutionThatCannotFitIsRefusedAndThePreviousOneKept) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const auto dir = std::filesystem::temp_directory_path() /
                     ("edacrt_viewer_memory_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    // 200 MB: the window's full resolution (1280x800) does not fit, half of it does. Starting
    // at full resolution is refused; after the refused change the render goes on at half.
    std::ofstream(dir / "script.txt")
        << "set resolution 0.5\nwait-spp 1\nset resolution 1\nwait-error\nwait-spp 3\nquit\n";
    const auto result =
        test::run_command("EDACRT_MEMORY_LIMIT=200000000 " +
                          viewer_under_xvfb("--hide-panels --script " +
                                            (dir / "script.txt").string() + " builtin:cornell"));
    std::filesystem::remove_all(dir);
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const std::string refusal = "edacrt_viewer: error: a 1280x800 path render needs about ";
    const std::size_t first = result.output.find(refusal);
    ASSERT_NE(first, std::string::npos) << result.output;
    EXPECT_NE(result.output.find("more than the 200 MB of EDACRT_MEMORY_LIMIT; choose a smaller "
                                 "size",
                                 first),
              std::string::npos)
        << result.output;
    EXPECT_NE(result.output.find(refusal, first + 1), std::string::npos) << "refused twice";
    EXPECT_NE(result.output.find("error shown: a 1280x800 path render needs about "),
              std::string::npos)
        << result.output;
    EXPECT_EQ(result.output.find("640x400 path render needs"), std::string::npos);
}

/// Runs a script in the viewer at a window size; returns the output.
test::CliResult run_viewer_script(const std::filesystem::path& dir, const std::string& script,
                                  int width, int height, const std::string& args) {
    std::ofstream(dir / "script.txt") << script;
    return test::run_command(xvfb_viewer(1920, 1080,
                                         "--width " + std::to_string(width) + " --height " +
                                             std::to_string(height) + " --script " +
                                             (dir / "script.txt").string() + " " + args));
}

TEST(ViewerScreenshots, DamagedBookmarksAreReportedAndTheFileLeftAlone) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const auto dir = std::filesystem::temp_directory_path() /
                     ("edacrt_viewer_bookmarks_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string damaged =
        R"({"version": 1, "scenes": {"builtin:cornell": [{"name": "a", "eye": [0, 0, 5], )"
        R"("look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 0}]}})";
    std::ofstream(dir / "bookmarks.json") << damaged;
    const auto result =
        run_viewer_script(dir, "wait-loaded\nquit\n", 1280, 800,
                          "--bookmarks " + (dir / "bookmarks.json").string() + " builtin:cornell");
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("[0]: skipped"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("moved to a .bak before bookmarks are next saved"),
              std::string::npos)
        << result.output;
    std::ifstream in(dir / "bookmarks.json");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), damaged);
    std::filesystem::remove_all(dir);
}

// The script's `bookmark NAME` writes the --bookmarks file; a file that cannot be written
// fails the script at its line.
TEST(ViewerScreenshots, AScriptSavesABookmarkOrFailsAtItsLine) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const test::TempDir dir;
    const std::filesystem::path file = dir.path() / "config" / "bookmarks.json";
    const auto saved = run_viewer_script(dir.path(), "wait-loaded\nbookmark front\nquit\n", 1280,
                                         800, "--bookmarks " + file.string() + " builtin:cornell");
    ASSERT_EQ(saved.exit_code, 0) << saved.output;
    const auto json = nlohmann::json::parse(std::ifstream(file));
    const auto& list = json["scenes"]["builtin:cornell"];
    ASSERT_EQ(list.size(), 1u) << json.dump();
    EXPECT_EQ(list[0]["name"], "front");
    EXPECT_EQ(list[0]["eye"].size(), 3u);

    // A bookmarks file under a regular file: its folder cannot be made.
    const std::filesystem::path blocked = dir.write("plain", "") / "bookmarks.json";
    const auto failed =
        run_viewer_script(dir.path(), "wait-loaded\nbookmark front\nquit\n", 1280, 800,
                          "--bookmarks " + blocked.string() + " builtin:cornell");
    EXPECT_EQ(failed.exit_code, 1) << failed.output;
    EXPECT_NE(failed.output.find("edacrt_viewer: error: script line 2: bookmarks not saved: " +
                                 blocked.string()),
              std::string::npos)
        << failed.output;
}

// A bounce batch end to end: `set batch` records it, the heat map shows it, the debugger follows
// the pixel's bounce ray, write-analysis writes the Statistics tab's figures; a batch the pass
// does not trace fails the script at its line.
TEST(ViewerScreenshots, AnyBatchIsAnalysedAndWritten) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const test::TempDir dir;
    const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
    const std::string script =
        "set max-depth 3\nwait-spp 1\nwrite-analysis " + file("camera.json") +
        "\nset batch bounce:1\nwait-analysis\nwrite-analysis " + file("bounce.json") +
        "\nview box\nwait-settled\ntab Heat_map\nwait-settled\nscreenshot " + file("heat.png") +
        "\nlayout " + file("heat.json") +
        "\ntab Traversal\npick-image 0.5 0.5\nwait-analysis\nwait-settled\nlayout " +
        file("layout.json") + "\nset batch shadow:0\nwait-analysis\nwrite-analysis " +
        file("shadow.json") + "\nset batch bounce:4\nwait-analysis\nwrite-analysis " +
        file("none.json") + "\n";
    const auto result =
        run_viewer_script(dir.path(), script, 1280, 800, kSanitizedResolution + "builtin:cornell");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("script line 23: no statistics of batch bounce:4: no batch "
                                 "bounce:4: paths end after max-depth 3 bounces"),
              std::string::npos)
        << result.output;
    const auto read = [&](const std::string& name) {
        std::ifstream in(file(name));
        return nlohmann::json::parse(in);
    };
    const nlohmann::json camera = read("camera.json"), bounce = read("bounce.json"),
                         shadow = read("shadow.json");
    EXPECT_EQ(camera["batch"], "camera");
    EXPECT_EQ(bounce["batch"], "bounce:1");
    EXPECT_EQ(shadow["batch"], "shadow:0");
    const std::uint64_t pixels =
        camera["width"].get<std::uint64_t>() * camera["height"].get<std::uint64_t>();
    EXPECT_EQ(camera["rays"], pixels);
    // The Cornell box is open at the front: some paths leave before bounce 1.
    EXPECT_GT(bounce["rays"].get<std::uint64_t>(), pixels / 4);
    EXPECT_LT(bounce["rays"].get<std::uint64_t>(), pixels);
    EXPECT_GT(shadow["rays"].get<std::uint64_t>(), 0u);
    for (const nlohmann::json* j : {&camera, &bounce, &shadow}) {
        EXPECT_FALSE((*j)["detail"]["levels"].empty());
        EXPECT_EQ((*j)["detail"]["per_ray"]["rays"], (*j)["rays"]);
    }
    // Incoherent bounce rays cost more tests per ray than camera rays.
    EXPECT_GT(bounce["detail"]["per_ray"]["ray_box_tests_mean"].get<double>(),
              camera["detail"]["per_ray"]["ray_box_tests_mean"].get<double>());
    EXPECT_TRUE(std::filesystem::exists(file("heat.png")));
    std::ifstream layout(file("layout.json"));
    const nlohmann::json drawn = nlohmann::json::parse(layout);
    EXPECT_TRUE(drawn["items"].contains("Analysis/batch")) << drawn.dump();
    // `tab` after `view box`: the tab is open by the time wait-settled lets the script go on.
    std::ifstream heat_layout(file("heat.json"));
    const nlohmann::json heat = nlohmann::json::parse(heat_layout);
    const auto& open = heat["tabs_open"];
    EXPECT_NE(std::find(open.begin(), open.end(), "Heat map"), open.end()) << open.dump();
    EXPECT_TRUE(drawn["errors_shown"].empty()) << drawn.dump();
}

// ImGui brings a tab forward a frame after it is asked for: wait-settled lets the script go on
// only once every tab asked for is drawn open (a heat map view made the next frame's layout
// look settled before the switch).
TEST(ViewerScreenshots, ATabAskedForIsOpenWhenTheScriptGoesOn) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const test::TempDir dir;
    const std::string layout = (dir.path() / "layout.json").string();
    const auto result = run_viewer_script(
        dir.path(),
        "wait-spp 1\nview box\nwait-settled\ntab Recursion\nwait-settled\nlayout " + layout + "\n",
        1280, 800,
        "--integrator primary " + (test::source_dir() / "assets/teapot/teapot.obj").string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    std::ifstream in(layout);
    const nlohmann::json drawn = nlohmann::json::parse(in);
    const auto& open = drawn["tabs_open"];
    EXPECT_NE(std::find(open.begin(), open.end(), "Recursion"), open.end()) << open.dump();
}

// `set font-scale` (Ctrl +/-) scales the panels' text and widgets; `set analysis-height` moves
// the split between the image and the analysis.
TEST(ViewerScreenshots, FontScaleAndTheSplitResizeThePanels) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const test::TempDir dir;
    const auto file = [&](const std::string& name) { return (dir.path() / name).string(); };
    const auto result = run_viewer_script(
        dir.path(),
        "wait-loaded\nwait-settled\nlayout " + file("plain.json") +
            "\nset font-scale 1.5\nset analysis-height 0.5\nwait-settled\nlayout " +
            file("scaled.json") + "\n",
        1280, 800, "builtin:cornell");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const auto read = [&](const std::string& name) {
        std::ifstream in(file(name));
        return nlohmann::json::parse(in);
    };
    const nlohmann::json plain = read("plain.json"), scaled = read("scaled.json");
    const double tab = plain["items"]["Scene/tab"]["h"].get<double>();
    // A tab is the font's height (13 units unscaled) and an unscaled padding: half a font more.
    EXPECT_NEAR(scaled["items"]["Scene/tab"]["h"].get<double>() - tab, 0.5 * 13.0, 1.0);
    EXPECT_NEAR(scaled["analysis"]["h"].get<double>(), 400.0, 1.0);
    EXPECT_NEAR(scaled["image"]["h"].get<double>(), 400.0, 1.0);
    EXPECT_LT(plain["analysis"]["h"].get<double>(), 399.0) << "sized to its tables before";
}

TEST(ViewerScreenshots, NoPanelCoversTheImageAndNoTableIsClippedAtTwoWindowSizes) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const auto dir = std::filesystem::temp_directory_path() /
                     ("edacrt_viewer_layout_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    // Every tab of both panels, a recording and a followed pixel (the widest tables), the
    // help overlay, the analysis collapsed; check-layout queries ImGui's windows and counts
    // table cells narrower than their text, and fails the script on any problem. Each check
    // waits until the tab is drawn and its columns have fitted their text (wait-settled).
    std::string script = "wait-spp 1\npick-image 0.5 0.3\nwait-analysis\n";
    for (const char* tab : {"Scene", "Camera", "Render", "EDACRT"})
        script += std::string("tab ") + tab + "\nwait-settled\ncheck-layout\n";
    for (const char* tab : {"Statistics", "Heat_map", "Recursion", "Traversal", "Frames"})
        script += std::string("tab ") + tab + "\nwait-settled\ncheck-layout\n";
    // The explorer against DACRT: its level table and differences too.
    script +=
        "set against dacrt\nwait-analysis\nset node 1\ntab Recursion\nwait-settled\ncheck-layout\n";
    script +=
        "help on\nwait-settled\ncheck-layout\nhelp off\nset analysis-height 0.7\ntab "
        "Statistics\nwait-settled\ncheck-layout\nanalysis closed\nwait-settled\n"
        "check-layout\n";
    for (const auto& [width, height] : {std::pair{1024, 640}, std::pair{1600, 900}}) {
        const auto result =
            run_viewer_script(dir, script, width, height,
                              kSanitizedResolution + "--integrator primary " +
                                  (test::source_dir() / "assets/teapot/teapot.obj").string());
        ASSERT_EQ(result.exit_code, 0) << width << "x" << height << "\n" << result.output;
        std::size_t checks = 0;
        for (std::size_t at = 0;
             (at = result.output.find("layout ok: 2 panels", at)) != std::string::npos; ++at)
            ++checks;
        EXPECT_EQ(checks, 13u) << result.output;
    }
    std::filesystem::remove_all(dir);
}

TEST(ViewerScreenshots, TheCopiedCommandLineRendersTheViewersImage) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const auto dir = std::filesystem::temp_directory_path() /
                     ("edacrt_viewer_roundtrip_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    // A moved camera, a parameter changed; saves into folders that do not exist yet.
    const auto saved = dir / "new" / "folder";
    const std::string script =
        "orbit 40 -25\nset seed 7\nset bins 4\nset spp 6\nwait-spp 6\n"
        "save-linear " +
        (saved / "view.pfm").string() + "\nsave-linear " + (saved / "view.exr").string() +
        "\nsave-view " + (saved / "view.png").string() + "\nwrite-command " +
        (dir / "command.txt").string() + "\nquit\n";
    const auto viewer = run_viewer_script(
        dir, script, 700, 500,
        "--integrator path " +
            (test::source_dir() / "assets/cornell-box/CornellBox-Original.obj").string());
    ASSERT_EQ(viewer.exit_code, 0) << viewer.output;
    std::ifstream in(dir / "command.txt");
    std::string command;
    std::getline(in, command);
    // The program beside the viewer, by its absolute path.
    const std::filesystem::path program = command.substr(0, command.find(" render "));
    EXPECT_TRUE(program.is_absolute()) << command;
    EXPECT_TRUE(std::filesystem::equivalent(program, EDACRT_CLI)) << command;
    EXPECT_NE(command.find("--bins 4"), std::string::npos) << command;
    EXPECT_NE(command.find("--seed 7"), std::string::npos) << command;
    // The same command with its output in the test's folder, pasted in another folder.
    command = command.substr(0, command.rfind(" --out ")) + " --out " + (dir / "cli.pfm").string();
    const auto cli = test::run_command("cd / && " + command);
    ASSERT_EQ(cli.exit_code, 0) << command << "\n" << cli.output;
    const Image a = read_pfm(saved / "view.pfm"), b = read_pfm(dir / "cli.pfm");
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    EXPECT_TRUE(a.pixels == b.pixels) << "the viewer's render and the command's differ";
    // The EXR goes through the CLI's image code: float, with the view in its header.
    ImageMetadata metadata;
    EXPECT_TRUE(read_exr(saved / "view.exr", &metadata).pixels == a.pixels);
    const auto has = [&](const std::string& name, const std::string& value) {
        return std::find(metadata.begin(), metadata.end(), std::pair(name, value)) !=
               metadata.end();
    };
    EXPECT_TRUE(has("software", "EDACRT Studio (edacrt_viewer)"));
    EXPECT_TRUE(has("spp", "6"));
    EXPECT_TRUE(has("seed", "7"));
    const Image shown = read_png(saved / "view.png");
    EXPECT_EQ(shown.width, a.width) << "the PNG is the image region as shown";
    EXPECT_EQ(shown.height, a.height);
    if (!HasFailure()) std::filesystem::remove_all(dir);
}

// The bundled animation: shown at two times, played for a few frames, every method compared on
// a frame; the layout holds with the timeline; the copied command renders the viewer's frame.
TEST(ViewerScreenshots, AnAnimationShowsItsFramesPlaysAndRoundTripsThroughTheCommandLine) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const auto dir = std::filesystem::temp_directory_path() /
                     ("edacrt_viewer_animation_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto file = [&](const char* name) { return (dir / name).string(); };
    const std::string script =
        "set time 0.5\nwait-spp 4\nsave-linear " + file("early.pfm") + "\nwrite-command " +
        file("command.txt") + "\nscreenshot " + file("early.png") +
        "\nset play 1\nwait-played 6\nset play 0\nset time 2.6\nwait-spp 4\nsave-linear " +
        file("late.pfm") + "\ncompare\nwait-compare\ntab Frames\nwait-settled\ncheck-layout\n" +
        "screenshot " + file("late.png") + "\n";
    const auto viewer = run_viewer_script(
        dir, script, 1024, 640,
        "--integrator primary --spp 4 --method bvh " +
            (test::source_dir() / "assets/animations/spot-and-teapot.anim.json").string());
    ASSERT_EQ(viewer.exit_code, 0) << viewer.output;
    EXPECT_NE(viewer.output.find("layout ok: 3 panels"), std::string::npos) << viewer.output;
    const Image early = read_pfm(file("early.pfm")), late = read_pfm(file("late.pfm"));
    ASSERT_EQ(early.width, late.width);
    EXPECT_FALSE(early.pixels == late.pixels) << "two times, one image";
    // The objects moved: a good share of the pixels changed.
    std::size_t changed = 0;
    for (std::size_t i = 0; i < early.pixels.size(); ++i)
        changed += glm::length(early.pixels[i] - late.pixels[i]) > 0.05f;
    EXPECT_GT(double(changed) / double(early.pixels.size()), 0.02);
    std::ifstream in(file("command.txt"));
    std::string command;
    std::getline(in, command);
    EXPECT_NE(command.find("--animate "), std::string::npos) << command;
    EXPECT_NE(command.find("--time 0.5 "), std::string::npos) << command;
    command = command.substr(0, command.rfind(" --out ")) + " --out " + file("cli.pfm");
    const auto cli = test::run_command("cd / && " + command);
    ASSERT_EQ(cli.exit_code, 0) << command << "\n" << cli.output;
    EXPECT_TRUE(read_pfm(file("cli.pfm")).pixels == early.pixels)
        << "the command renders another frame than the viewer showed";
    if (!HasFailure()) std::filesystem::remove_all(dir);
}

TEST(ViewerScreenshots, ABrokenSceneOnTheCommandLineFailsClearly) {
    const auto result = test::run_command(EDACRT_VIEWER " /no/such/scene.obj");
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("/no/such/scene.obj"), std::string::npos) << result.output;
}

// A save that fails fails the script at its line; a render that fails ends a wait with its
// error (c-i 0 passes `set`'s range but not the tracer's check) instead of five minutes.
TEST(ViewerScreenshots, AFailedSaveOrRenderFailsTheScriptAtItsLine) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const test::TempDir dir;
    const auto in_the_way = dir.write("file", "a file where a folder should be");
    const struct {
        std::string script, message;
    } cases[] = {
        {"wait-spp 1\nsave-linear " + (in_the_way / "x.pfm").string() + "\nquit\n",
         "edacrt_viewer: error: script line 2: " + in_the_way.string() + "/x.pfm: "},
        {"set c-i 0\nwait-spp 2\nquit\n",
         "edacrt_viewer: error: script line 2: the render failed: EDACRT parameter c-i (C_I) "
         "must be positive"},
        // An output over the script being run (tests/viewer_files_test.cpp: every input).
        {"wait-spp 1\nsave-view " + (dir.path() / "script.txt").string() + "\nquit\n",
         "edacrt_viewer: error: script line 2: save-view " + (dir.path() / "script.txt").string() +
             " is the script input: writing it would replace what is read"},
        {"wait-spp 1\nscreenshot " + (dir.path() / "script.txt").string() + "\nquit\n",
         "edacrt_viewer: error: screenshot " + (dir.path() / "script.txt").string() +
             " is the script input"},
    };
    for (const auto& c : cases) {
        const auto start = std::chrono::steady_clock::now();
        const auto result = run_viewer_script(dir.path(), c.script, 320, 240,
                                              "--hide-panels --integrator primary builtin:cornell");
        EXPECT_EQ(result.exit_code, 1) << c.script << "\n" << result.output;
        EXPECT_NE(result.output.find(c.message), std::string::npos) << c.script << "\n"
                                                                    << result.output;
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::minutes(1));
        std::ifstream script(dir.path() / "script.txt");
        EXPECT_EQ(std::string(std::istreambuf_iterator<char>(script), {}), c.script);
    }
}

// As edacrt reports its command line (tests/command_line_cli_test.cpp); no window is opened.
TEST(ViewerCommandLine, VersionAndUsageErrorsAsTheCliReportsThem) {
    const auto version = test::run_command(EDACRT_VIEWER " --version");
    EXPECT_EQ(version.exit_code, 0) << version.output;
    EXPECT_EQ(version.output, "edacrt_viewer 0.1\n");
    const auto help = test::run_command(EDACRT_VIEWER " --help");
    EXPECT_EQ(help.exit_code, 0) << help.output;
    EXPECT_NE(help.output.find("70 internal error"), std::string::npos) << help.output;
    for (const char* args : {" --spp abc", " --bogus", " --width 10"}) {
        const auto result = test::run_command(std::string(EDACRT_VIEWER) + args);
        EXPECT_EQ(result.exit_code, 2) << args << "\n" << result.output;
        EXPECT_EQ(result.output.rfind("edacrt_viewer: error: ", 0), 0u) << result.output;
        EXPECT_NE(result.output.find("\nrun 'edacrt_viewer --help'"), std::string::npos)
            << result.output;
    }
    // Values refused after parsing, and unknown enum names, are usage errors too.
    for (const char* args : {" --shutter -1", " --speed 9", " --time nan", " --method foo",
                             " builtin:sphere --play"}) {
        const auto result = test::run_command("timeout 20 " EDACRT_VIEWER + std::string(args));
        EXPECT_EQ(result.exit_code, 2) << args << "\n" << result.output;
        EXPECT_EQ(result.output.rfind("edacrt_viewer: error: ", 0), 0u) << result.output;
    }
    // Animation flags without an animation, as edacrt refuses --frames/--time/--shutter: one
    // line naming the flag.
    for (const char* flag : {"--shutter 0.1", "--speed 2", "--update rebuild"}) {
        const auto result =
            test::run_command("timeout 20 " EDACRT_VIEWER " builtin:sphere " + std::string(flag));
        EXPECT_EQ(result.exit_code, 2) << flag << "\n" << result.output;
        EXPECT_EQ(result.output, "edacrt_viewer: error: " +
                                     std::string(flag).substr(0, std::string(flag).find(' ')) +
                                     " needs an animated scene (--animate, or an animation "
                                     "file)\n");
    }
    // An unknown animation lists the kinds on one line (its help had \x0A for newlines).
    const auto bogus =
        test::run_command("timeout 20 " EDACRT_VIEWER " builtin:sphere --animate bogus");
    EXPECT_NE(bogus.exit_code, 0);
    EXPECT_EQ(bogus.output.rfind("edacrt_viewer: error: unknown animation 'bogus'; available: "
                                 "wave[:",
                                 0),
              0u)
        << bogus.output;
    EXPECT_EQ(std::count(bogus.output.begin(), bogus.output.end(), '\n'), 1) << bogus.output;
    EXPECT_EQ(bogus.output.find("\\x0A"), std::string::npos) << bogus.output;
}

// Names from files (a script's words, a scene path) reach the terminal escaped: an ESC byte
// in them cannot send escape codes.
TEST(ViewerCommandLine, ErrorsQuotingFilesAreEscaped) {
    const test::TempDir dir;
    const std::string esc = "\x1b[2J";
    const auto expect_escaped = [](const test::CliResult& result, const std::string& message) {
        EXPECT_EQ(result.exit_code, 1) << result.output;
        EXPECT_NE(result.output.find(message), std::string::npos) << result.output;
        EXPECT_EQ(result.output.find('\x1b'), std::string::npos) << result.output;
    };
    // Both refused before any window opens.
    const std::filesystem::path script = dir.write("parse.txt", "frames 1\nfly" + esc + "away\n");
    expect_escaped(test::run_command(EDACRT_VIEWER " --script " + script.string()),
                   "edacrt_viewer: error: " + script.string() +
                       ":2: unknown script command 'fly\\x1B[2Jaway'");
    const std::string scene = (dir.path() / ("no" + esc + "scene.obj")).string();
    expect_escaped(test::run_command(EDACRT_VIEWER " '" + scene + "'"), "no\\x1B[2Jscene.obj");
    // A script line that fails while the viewer runs.
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    expect_escaped(run_viewer_script(dir.path(), "wait-loaded\nset method " + esc + "x\nquit\n",
                                     1280, 800, "builtin:cornell"),
                   "edacrt_viewer: error: script line 2: ");
}

// The viewer shows a scene's map_Kd as the CLI does (one engine path): a square whose texture
// has red, green, blue and white quadrants, twice across, under the default of a scene without
// emitters (ambient occlusion times the albedo).
TEST(ViewerScreenshots, TexturesShowInTheViewer) {
    if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup installs it)";
    const test::TempDir dir;
    // Quadrants of 2 x 2 texels: bilinear magnification keeps the middle of each one pure.
    const unsigned char top[] = {255, 0, 0, 255, 0, 0, 0, 255, 0, 0, 255, 0};
    const unsigned char bottom[] = {0, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255, 255};
    std::string ppm = "P6\n4 4\n255\n";
    for (const unsigned char* row : {top, top, bottom, bottom}) ppm.append((const char*)row, 12);
    dir.write("t.ppm", ppm);
    dir.write("m.mtl", "newmtl m\nKd 1 1 1\nmap_Kd t.ppm\n");
    const auto obj = dir.write("square.obj",
                               "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                               "vt 0 0\nvt 2 0\nvt 2 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3 4/4\n");
    const auto shot = dir.path() / "textured.png";
    const auto result = run_viewer_script(
        dir.path(), "panels hidden\nwait-spp 2\nscreenshot " + shot.string() + "\nquit\n", 640, 400,
        kSanitizedResolution + obj.string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const Image image = read_png(shot.string());
    std::size_t red = 0, green = 0, blue = 0;
    for (const glm::vec3& p : image.pixels) {
        red += p.x > 0.3f && p.x > 4.0f * (p.y + p.z);
        green += p.y > 0.3f && p.y > 4.0f * (p.x + p.z);
        blue += p.z > 0.3f && p.z > 4.0f * (p.x + p.y);
    }
    const std::size_t some = image.pixels.size() / 200;  // the square is about a quarter
    EXPECT_GT(red, some);
    EXPECT_GT(green, some);
    EXPECT_GT(blue, some);
}

}  // namespace
}  // namespace edacrt
