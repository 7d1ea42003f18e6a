// The viewer core's layout, bookmarks, command line and stale-recording rule (no window).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "bookmarks.h"
#include "command_line.h"
#include "key_presses.h"
#include "layout.h"
#include "panels/columns.h"
#include "scene/builtin_scenes.h"
#include "script_runner.h"
#include "util/error.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

TEST(Layout, PanelsTileTheWindowAndNeverOverlapTheImage) {
    for (float width : {320.0f, 640.0f, 1024.0f, 1280.0f, 1600.0f, 2560.0f, 7680.0f})
        for (float height : {240.0f, 480.0f, 640.0f, 800.0f, 900.0f, 1440.0f, 4320.0f})
            for (bool open : {true, false})
                for (bool animated : {false, true})
                    for (float em : {13.0f, 20.0f}) {
                        const Layout l =
                            compute_layout({width, height, em, em + 6.0f, false, open, animated});
                        const Rect window{0, 0, width, height};
                        SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height));
                        EXPECT_FALSE(l.image.empty());
                        EXPECT_GE(l.image.w, 0.45f * width - 0.5f);
                        EXPECT_GE(l.image.h, (animated ? 0.26f : 0.4f) * height - 0.5f);
                        EXPECT_EQ(l.timeline.empty(), !animated);
                        for (const Rect& r : {l.controls, l.analysis, l.image, l.timeline})
                            EXPECT_TRUE(r.empty() || window.contains(r));
                        for (const Rect& r : {l.controls, l.analysis, l.timeline})
                            EXPECT_FALSE(r.overlaps(l.image));
                        EXPECT_FALSE(l.controls.overlaps(l.analysis));
                        EXPECT_FALSE(l.timeline.overlaps(l.analysis));
                        EXPECT_FALSE(l.timeline.overlaps(l.controls));
                        if (animated) {  // the timeline spans the image, right under it
                            EXPECT_EQ(l.timeline.x, l.image.x);
                            EXPECT_EQ(l.timeline.w, l.image.w);
                            EXPECT_EQ(l.timeline.y, l.image.bottom());
                            EXPECT_GE(l.timeline.h, std::min(2.0f * (em + 6.0f), 0.05f * height));
                        }
                        // Together they cover the window.
                        const float area = l.controls.w * l.controls.h +
                                           l.analysis.w * l.analysis.h + l.image.w * l.image.h +
                                           l.timeline.w * l.timeline.h;
                        EXPECT_NEAR(area, width * height, 1e-3f * width * height);
                        if (!open) {
                            EXPECT_LE(l.analysis.h, em + 6.0f);
                        }
                    }
    const Layout hidden = compute_layout({1280, 800, 13, 19, true, true});
    EXPECT_TRUE(hidden.controls.empty());
    EXPECT_TRUE(hidden.analysis.empty());
    EXPECT_EQ(hidden.image.w, 1280.0f);
    EXPECT_EQ(hidden.image.h, 800.0f);
}

// The dragged split: the analysis takes its share of the height, within bounds that keep a sixth
// for the image; collapsed, only its title bar, whatever the share.
TEST(Layout, TheDraggedSplitSetsTheAnalysisHeight) {
    const auto analysis = [](float share, bool open = true, float height = 800.0f) {
        return compute_layout({1280.0f, height, 13.0f, 19.0f, false, open, false, share})
            .analysis.h;
    };
    EXPECT_FLOAT_EQ(analysis(0.5f), 400.0f);
    EXPECT_FLOAT_EQ(analysis(0.25f), 200.0f);
    EXPECT_FLOAT_EQ(analysis(0.99f), 800.0f * kMaxAnalysisShare);
    EXPECT_FLOAT_EQ(analysis(0.001f), 800.0f * kMinAnalysisShare);
    EXPECT_FLOAT_EQ(analysis(0.001f, true, 100.0f), 19.0f) << "never less than its title bar";
    EXPECT_FLOAT_EQ(analysis(0.5f, false), 19.0f);
    EXPECT_FLOAT_EQ(analysis(0.0f), compute_layout({1280.0f, 800.0f, 13.0f, 19.0f}).analysis.h);
    for (const float share : {0.05f, 0.3f, 0.7f, 0.95f}) {
        const Layout l = compute_layout({1280.0f, 800.0f, 13.0f, 19.0f, false, true, true, share});
        EXPECT_FALSE(l.image.overlaps(l.analysis));
        EXPECT_FALSE(l.timeline.overlaps(l.analysis));
        EXPECT_GE(l.image.h, 0.1f * 800.0f);
        EXPECT_NEAR(l.image.h + l.timeline.h + l.analysis.h, 800.0f, 1e-3f);
    }
}

TEST(StepThrough, PlayingAdvancesAtItsRateAndStopsAtTheLastNode) {
    double carry = 0.0;
    bool playing = true;
    int step = advance_step(3, 20, 10.0f, 0.25, carry, playing);  // 2.5 nodes
    EXPECT_EQ(step, 5);
    EXPECT_DOUBLE_EQ(carry, 0.5);
    step = advance_step(step, 20, 10.0f, 0.05, carry, playing);  // the half node carried
    EXPECT_EQ(step, 6);
    EXPECT_TRUE(playing);
    step = advance_step(step, 20, 10.0f, 5.0, carry, playing);
    EXPECT_EQ(step, 20);
    EXPECT_FALSE(playing);
    EXPECT_EQ(advance_step(7, 20, 10.0f, 1.0, carry, playing), 7) << "paused";
    playing = true;
    EXPECT_EQ(advance_step(7, 20, 10.0f, -1.0, carry, playing), 7) << "no time, no step";
}

TEST(Layout, CtrlPlusAndMinusStepTheFontScaleWithinItsBounds) {
    EXPECT_FLOAT_EQ(step_font_scale(1.0f, 1), kFontScaleStep);
    EXPECT_FLOAT_EQ(step_font_scale(step_font_scale(1.0f, 3), -3), 1.0f);
    EXPECT_FLOAT_EQ(step_font_scale(1.0f, 100), kMaxFontScale);
    EXPECT_FLOAT_EQ(step_font_scale(1.0f, -100), kMinFontScale);
    KeyPresses keys;
    keys.press(45, 2, false);  // Ctrl + '-'
    keys.press(45, 0, false);  // '-'
    EXPECT_EQ(keys.count(45, 2), 1) << "Ctrl held";
    EXPECT_EQ(keys.count(45, 0, false, 2), 1) << "without Ctrl: the fly speed's";
    EXPECT_EQ(keys.count(45), 2);
}

TEST(Layout, ProblemsNameThePanelThatOverlapsLeavesOrClips) {
    const Layout l = compute_layout({1024, 640, 13, 19, false, true});
    EXPECT_TRUE(layout_problems(l, 1024, 640, {{"Controls", l.controls, 0}}).empty());
    const auto overlap =
        layout_problems(l, 1024, 640, {{"Stats", {l.image.x + 10, 10, 100, 100}, 0}});
    ASSERT_EQ(overlap.size(), 1u);
    EXPECT_NE(overlap[0].find("Stats"), std::string::npos);
    EXPECT_NE(overlap[0].find("overlaps the image"), std::string::npos);
    EXPECT_EQ(layout_problems(l, 1024, 640, {{"Wide", {0, 600, 1100, 10}, 0}}).size(), 1u);
    const auto clipped = layout_problems(l, 1024, 640, {{"Analysis", l.analysis, 3}});
    ASSERT_EQ(clipped.size(), 1u);
    EXPECT_NE(clipped[0].find("3 table cells clipped"), std::string::npos);
}

TEST(Bookmarks, SaveLoadReplaceAndRemovePerScene) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("edacrt_bookmarks_" + std::to_string(::getpid()));
    const std::string path = (dir / "sub" / "bookmarks.json").string();
    Bookmarks b;
    const Camera a{{1.1f, 2.2f, 3.3f}, {0.1f, 0.2f, 0.3f}, {0, 1, 0}, 33.3f};
    const Camera c{{-5e-7f, 1e15f, 7}, {0, 0, 0}, {0, 0, 1}, 90.0f};
    b.put("builtin:cornell", {"front", a});
    b.put("builtin:cornell", {"top", c});
    b.put("builtin:cornell", {"front", c});  // replaces
    b.put("/tmp/x.obj", {"x", a});
    b.save(path);  // creates the folders
    Bookmarks read;
    read.load(path);
    ASSERT_EQ(read.of("builtin:cornell").size(), 2u);
    EXPECT_EQ(read.of("builtin:cornell")[0].camera, c) << "floats read back exactly";
    EXPECT_EQ(read.of("/tmp/x.obj")[0].camera, a);
    EXPECT_TRUE(read.of("builtin:sphere").empty());
    read.remove("builtin:cornell", "front");
    ASSERT_EQ(read.of("builtin:cornell").size(), 1u);
    EXPECT_EQ(read.of("builtin:cornell")[0].name, "top");

    // Problems are reported, not thrown (tests/viewer_files_test.cpp has the details).
    Bookmarks missing;
    EXPECT_TRUE(missing.load((dir / "none.json").string()).empty());
    std::ofstream(dir / "bad.json") << "{\"scenes\": {\"s\": [{\"name\": 3}]}}";
    EXPECT_EQ(missing.load((dir / "bad.json").string()).size(), 1u);
    std::ofstream(dir / "garbage.json") << "not json";
    EXPECT_EQ(missing.load((dir / "garbage.json").string()).size(), 1u);
    // A camera that cannot form an image is refused, not loaded.
    std::ofstream(dir / "degenerate.json")
        << R"({"scenes": {"s": [{"name": "n", "eye": [0,0,0], "look_at": [0,0,0], "up": [0,1,0], "fov": 45}]}})";
    EXPECT_EQ(missing.load((dir / "degenerate.json").string()).size(), 1u);
    EXPECT_TRUE(missing.of("s").empty());
    std::filesystem::remove_all(dir);
}

TEST(CommandLine, CarriesTheExactCameraAndTheChangedParameters) {
    ViewCommand v;
    v.scene = "/data/my scenes/it's.obj";
    v.camera = {{0.1f, 1.0f / 3.0f, -2e-8f}, {1, 2, 3}, {0, 1, 0}, 47.5f};
    v.settings.width = 640;
    v.settings.height = 360;
    v.settings.integrator = Integrator::ao;
    v.settings.ao_samples = 9;
    v.spp = 12;
    v.params.bins = 16;
    const std::string line = render_command_line(v);
    EXPECT_EQ(line.rfind("edacrt render --scene '/data/my scenes/it'\\''s.obj' ", 0), 0u) << line;
    for (const char* part :
         {" --integrator ao", " --ao-samples 9", " --spp 12", " --width 640", " --height 360",
          " --eye 0.100000001,0.333333343,-1.99999999e-08", " --fov 47.5", " --bins 16"})
        EXPECT_NE(line.find(part), std::string::npos) << part << " in " << line;
    // Only parameters that differ from their defaults.
    EXPECT_EQ(line.find("--leaf-rays"), std::string::npos) << line;
}

TEST(CommandLine, NamesTheProgramAndTheSceneByAbsolutePaths) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("edacrt_program_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    // Beside the viewer, the build's edacrt; with none there, the one on PATH.
    EXPECT_EQ(edacrt_program(dir / "edacrt_viewer"), "edacrt");
    std::ofstream(dir / "edacrt") << "";
    EXPECT_EQ(edacrt_program(dir / "edacrt_viewer"), (dir / "edacrt").string());
    EXPECT_EQ(edacrt_program({}), "edacrt");
    ViewCommand v;
    v.program = (dir / "my tools" / "edacrt").string();
    v.scene = "scenes/../scenes/a b.obj";
    const std::string line = render_command_line(v);
    EXPECT_EQ(
        line.rfind("'" + v.program + "' render --scene '" +
                       (std::filesystem::current_path() / "scenes" / "a b.obj").string() + "' ",
                   0),
        0u)
        << line;
    v.scene = "builtin:sphere:subdiv=2";
    EXPECT_NE(render_command_line(v).find(" --scene builtin:sphere:subdiv=2 "), std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST(CommandLine, RunsAsPastedFromAnotherFolder) {
    const std::string program = edacrt_program(this_executable());
    if (program == "edacrt") GTEST_SKIP() << "no edacrt beside " << this_executable();
    const auto dir =
        std::filesystem::temp_directory_path() / ("edacrt_pasted_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "one triangle.obj") << "v -1 -1 -3\nv 1 -1 -3\nv 0 1 -3\nf 1 2 3\n";
    ViewCommand v;
    v.program = program;
    // Relative to this process's folder, as the viewer's path field may hold it.
    v.scene = std::filesystem::relative(dir / "one triangle.obj").string();
    v.settings.width = 8;
    v.settings.height = 6;
    v.camera = {{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60.0f};
    v.out = (dir / "view.png").string();
    const int status = std::system(("cd / && " + render_command_line(v) + " -q").c_str());
    EXPECT_EQ(status, 0) << render_command_line(v);
    EXPECT_TRUE(std::filesystem::exists(dir / "view.png"));
    std::filesystem::remove_all(dir);
}

TEST(AnalysisTables, EveryColumnExplainsItself) {
    EXPECT_EQ(all_table_columns().size(), 7u);
    for (std::span<const Column> table : all_table_columns()) {
        ASSERT_FALSE(table.empty());
        std::set<std::string> names;
        for (const Column& c : table) {
            SCOPED_TRACE(c.name);
            EXPECT_TRUE(names.insert(c.name).second) << "a column named twice";
            const std::string help = c.help;
            // A sentence of its own, longer than the header it explains.
            EXPECT_GT(help.size(), std::string(c.name).size() + 8);
            EXPECT_EQ(help.back(), '.');
        }
    }
    EXPECT_EQ(level_columns().size(), 17u);   // the Statistics table draws 17 cells per row
    EXPECT_EQ(against_columns().size(), 7u);  // the level, then A and B of three figures
    // The compact set keeps what the paper's mechanism turns on: skipped filters, sampling and
    // filter box tests, triangle tests, both alphas and the time.
    std::set<std::string> compact;
    for (const Column& c : level_columns())
        if (!c.detail) compact.insert(c.name);
    EXPECT_EQ(compact,
              (std::set<std::string>{"level", "nodes", "rays in", "skipped", "tris", "sample box",
                                     "filter box", "tri tests", "alpha est", "alpha true", "ms"}));
}

TEST(KeyPresses, ATapWithinOneFrameCountsOnce) {
    constexpr int kH = 72, kSlash = 47, kRight = 262, kShift = 1;  // GLFW's codes
    KeyPresses keys;
    // Press and release both came before the frame read them: the press is kept.
    keys.press(kH, 0, false);
    EXPECT_TRUE(keys.pressed(kH));
    EXPECT_FALSE(keys.pressed(kSlash));
    keys.press(kSlash, kShift, false);  // '?'
    EXPECT_TRUE(keys.pressed(kSlash, kShift));
    EXPECT_TRUE(keys.pressed(kSlash));
    // Auto-repeats count only where asked for (stepping), not as toggles.
    keys.press(kRight, 0, false);
    keys.press(kRight, 0, true);
    keys.press(kRight, 0, true);
    EXPECT_EQ(keys.count(kRight), 1);
    EXPECT_EQ(keys.count(kRight, 0, true), 3);
    keys.clear();
    EXPECT_FALSE(keys.pressed(kH));
    EXPECT_EQ(keys.count(kRight, 0, true), 0);
    keys.press(kSlash, 0, false);  // '/' without Shift is not '?'
    EXPECT_FALSE(keys.pressed(kSlash, kShift));
}

TEST(Analysis, StaleOnceTheViewSceneSizeSeedMethodOrParametersChange) {
    auto scene = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    RenderRequest r;
    r.scene = scene;
    r.camera = *scene->camera;
    r.settings.width = 64;
    r.settings.height = 48;
    Analysis a;
    a.scene = scene;
    a.camera = r.camera;
    a.width = 64;
    a.height = 48;
    EXPECT_FALSE(analysis_stale(a, r, BatchId{}));
    auto moved = r;
    moved.camera.eye.x += 0.01f;
    EXPECT_TRUE(analysis_stale(a, moved, BatchId{}));
    auto resized = r;
    resized.settings.width = 65;
    EXPECT_TRUE(analysis_stale(a, resized, BatchId{}));
    auto reseeded = r;
    reseeded.settings.seed = 1;
    EXPECT_TRUE(analysis_stale(a, reseeded, BatchId{}));
    auto other = r;
    other.method = Method::dacrt;
    EXPECT_TRUE(analysis_stale(a, other, BatchId{}));
    auto params = r;
    params.params.bins = 5;
    EXPECT_TRUE(analysis_stale(a, params, BatchId{}));
    auto rescened = r;
    rescened.scene = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    EXPECT_TRUE(analysis_stale(a, rescened, BatchId{}));
    // Only what defines the batch: more samples do not make it stale.
    auto more = r;
    more.spp_target = 99;
    EXPECT_FALSE(analysis_stale(a, more, BatchId{}));
}

TEST(Analysis, TheTintMarksANodesPixelsAndTheHitsFoundSoFar) {
    // A 4x3 image, the batch a 2x2 crop at (1, 1): rays 0..3 are pixels 5, 6, 9, 10.
    auto detail = std::make_shared<TraceDetail>();
    detail->nodes.resize(3);
    detail->nodes[1].rays = 2;
    detail->nodes[1].ray_ids = 0;
    detail->node_ray_ids = {3, 1};
    detail->nodes[2].rays = 1;  // no ids recorded (past the budget)
    detail->hit_node = {2, -1, 1, 1};
    Analysis a;
    a.detail = detail;
    a.width = 4;
    a.height = 3;
    a.crop_x = a.crop_y = 1;
    a.crop_w = a.crop_h = 2;
    a.pixels = {5, 6, 9, 10};
    EXPECT_EQ(a.pixel_of(3), 10u);
    const auto tint = explorer_tint(a, 1, 1);
    const std::vector<float> expected = {0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 1, 0};
    EXPECT_EQ(tint, expected) << "node 1's rays over the hits found by node 1";
    const auto later = explorer_tint(a, -1, 2);
    EXPECT_EQ(later, (std::vector<float>{0, 0, 0, 0, 0, 2, 0, 0, 0, 2, 2, 0}));
    EXPECT_EQ(explorer_tint(a, 2, -1), std::vector<float>(12, 0.0f)) << "no ids, no tint";
}

TEST(Convergence, RelativeRmsChangeOfAPass) {
    Image a(2, 1), b(2, 1);
    b.pixels = {glm::vec3(1.0f), glm::vec3(1.0f)};
    a.pixels = {glm::vec3(1.0f), glm::vec3(1.5f)};
    // Difference energy 3 * 0.25, image energy 6: sqrt(0.125).
    EXPECT_NEAR(relative_rms_change(a, b), std::sqrt(0.125), 1e-12);
    EXPECT_EQ(relative_rms_change(b, b), 0.0);
    EXPECT_EQ(relative_rms_change(a, Image(2, 1)), 0.0) << "a black image: no scale";
    a.pixels[0].x = std::numeric_limits<float>::quiet_NaN();  // skipped, not propagated
    EXPECT_TRUE(std::isfinite(relative_rms_change(a, b)));
}

TEST(ScriptRunner, StepsChangeTheStateAndCheckLayoutFailsOnAProblem) {
    ViewerState s;
    ScriptRunner runner(
        parse_script("set bins 12\ntab Heat_map\npanels hidden\nanalysis closed\n"
                     "pick 10 20\ncheck-layout\nquit\n",
                     "test"));
    std::string screenshot;
    bool quit = false;
    runner.step(s, {}, screenshot, quit);  // a `set` ends the frame's steps
    EXPECT_EQ(s.ui.params.bins, 12);
    runner.step(s, {}, screenshot, quit);  // so do tab, panels, analysis (view, help)
    EXPECT_EQ(s.select_tabs, std::vector<std::string>{"Heat map"});
    EXPECT_FALSE(s.panels_hidden) << "the next frame draws the tab first";
    runner.step(s, {}, screenshot, quit);
    EXPECT_TRUE(s.panels_hidden);
    EXPECT_TRUE(s.analysis_open);
    runner.step(s, {}, screenshot, quit);
    s.layout_problems = {"Analysis overlaps the image"};
    EXPECT_THROW(runner.step(s, {}, screenshot, quit), InputError);
    EXPECT_TRUE(s.panels_hidden);
    EXPECT_FALSE(s.analysis_open);
    const auto pick = runner.take_pick();
    ASSERT_TRUE(pick);
    EXPECT_EQ(pick->x, 10.0f);
    EXPECT_EQ(pick->y, 20.0f);
    s.layout_problems.clear();
    runner.step(s, {}, screenshot, quit);  // the failed check-layout again, now fine
    EXPECT_TRUE(quit);
    EXPECT_FALSE(runner.active());
}

TEST(Settings, ScriptSettingsReachTheStateAndBadOnesAreRefused) {
    ViewerState s;
    apply_setting(s, "bins", "12");
    EXPECT_EQ(s.ui.params.bins, 12);
    apply_setting(s, "method", "bvh");
    EXPECT_EQ(s.ui.method, Method::bvh);
    EXPECT_THROW(apply_setting(s, "bins", "1e9"), InputError);
    EXPECT_THROW(apply_setting(s, "spp", "many"), InputError);
    EXPECT_THROW(apply_setting(s, "no-such-key", "1"), InputError);
    EXPECT_EQ(parse_enum_or_throw(kViews, "depth"), View::depth);
    EXPECT_THROW(parse_enum_or_throw(kViews, "x-ray"), InputError);
}

}  // namespace
}  // namespace edacrt::app
