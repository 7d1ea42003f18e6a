// The viewer's window-free parts: the render worker under a storm of parameter changes, the
// orbit camera, heat-map values, the script parser.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <thread>

#include "bookmarks.h"
#include "enum_table_checks.h"
#include "heatmap.h"
#include "input_error.h"
#include "orbit_camera.h"
#include "render/benchmark_rays.h"
#include "render_worker.h"
#include "scene/builtin_scenes.h"
#include "script.h"
#include "script_runner.h"
#include "temp_dir.h"
#include "util/error.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

RenderRequest small_request(std::shared_ptr<const Scene> scene) {
    RenderRequest r;
    r.scene = std::move(scene);
    r.camera = *r.scene->camera;
    r.settings.width = 24;
    r.settings.height = 16;
    r.settings.max_depth = 3;
    r.spp_target = 4;
    r.threads = 1;  // the race under test is between the UI and the worker thread
    return r;
}

// Only a guard against a hang: every wait below ends on a condition, not on time.
constexpr std::chrono::minutes kTimeout(1);

/// Waits for a full-resolution frame of `request` with at least `spp` (or an error).
std::shared_ptr<const Frame> wait_for(const RenderWorker& worker, std::uint64_t request, int spp) {
    const auto deadline = std::chrono::steady_clock::now() + kTimeout;
    while (std::chrono::steady_clock::now() < deadline) {
        const auto frame = worker.latest();
        if (frame && frame->request == request &&
            (!frame->error.empty() || (!frame->preview && frame->spp >= spp)))
            return frame;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return nullptr;
}

TEST(RenderWorker, RendersPreviewThenAccumulatesToTheTarget) {
    RenderWorker worker;
    const auto scene = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    const std::uint64_t id = worker.submit(small_request(scene));
    const auto frame = wait_for(worker, id, 4);
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->error, "");
    EXPECT_EQ(frame->spp, 4);
    EXPECT_EQ(frame->image.width, 24);
    ASSERT_TRUE(frame->detail);
    EXPECT_EQ(frame->detail->rays.size(), 24u * 16u);  // one per pixel
    EXPECT_FALSE(frame->detail->levels.empty());       // edacrt: per-level table
    ASSERT_TRUE(worker.wait_idle(kTimeout));           // stops at the target
    EXPECT_EQ(worker.latest()->spp, 4);
}

TEST(RenderWorker, PauseStopsAccumulatingAndResumeKeepsTheFilm) {
    RenderWorker worker;
    RenderRequest request =
        small_request(std::make_shared<const Scene>(make_builtin_scene("builtin:cornell")));
    request.spp_target = 1 << 20;  // not reached: only the pause stops the worker
    const std::uint64_t id = worker.submit(request);
    ASSERT_TRUE(wait_for(worker, id, 2));
    worker.set_paused(true);
    ASSERT_TRUE(worker.wait_idle(kTimeout));  // the pass in flight has ended, no other starts
    const int paused_at = worker.latest()->spp;
    EXPECT_GE(paused_at, 2);
    worker.set_paused(false);
    // Resuming goes on from the paused film: no frame of this request shows fewer samples.
    const auto deadline = std::chrono::steady_clock::now() + kTimeout;
    int spp = paused_at;
    while (spp < paused_at + 4 && std::chrono::steady_clock::now() < deadline) {
        const auto frame = worker.latest();
        ASSERT_EQ(frame->request, id);
        ASSERT_GE(frame->spp, paused_at);
        spp = frame->spp;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_GE(spp, paused_at + 4);
    worker.set_paused(true);
    EXPECT_TRUE(worker.wait_idle(kTimeout));
}

TEST(RenderWorker, IdleAgainWhenResumedAtTheTarget) {
    RenderWorker worker;
    const std::uint64_t id = worker.submit(
        small_request(std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"))));
    ASSERT_TRUE(wait_for(worker, id, 4));
    worker.set_paused(true);
    worker.set_paused(false);  // nothing left to do
    ASSERT_TRUE(worker.wait_idle(kTimeout));
    EXPECT_EQ(worker.latest()->spp, 4);
}

TEST(RenderWorker, BadParametersArriveAsAnErrorFrame) {
    RenderWorker worker;
    RenderRequest request =
        small_request(std::make_shared<const Scene>(make_builtin_scene("builtin:cornell")));
    request.params.bins = 1;
    const auto frame = wait_for(worker, worker.submit(request), 1);
    ASSERT_TRUE(frame);
    EXPECT_NE(frame->error.find("bins"), std::string::npos) << frame->error;
}

TEST(RenderWorker, SurvivesAThousandRandomParameterChanges) {
    // The UI thread changes everything while the worker renders; no race (run under
    // ThreadSanitizer by scripts/test), no hang, and the last request is rendered exactly.
    RenderWorker worker;
    const auto cornell = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    const auto sphere =
        std::make_shared<const Scene>(make_builtin_scene("builtin:sphere:subdiv=2"));
    std::mt19937 rng(7);
    const Method methods[] = {Method::edacrt, Method::dacrt, Method::bvh, Method::naive};
    const Integrator integrators[] = {Integrator::primary, Integrator::ao, Integrator::path};
    RenderRequest request = small_request(cornell);
    std::uint64_t id = 0;
    for (int i = 0; i < 1000; ++i) {
        request.scene = rng() % 2 ? cornell : sphere;
        request.camera = cornell->camera.value();
        request.camera.eye.x += float(rng() % 100) * 0.01f;
        request.method = methods[rng() % 4];
        request.settings.integrator = integrators[rng() % 3];
        request.params.bins = 2 + int(rng() % 30);
        request.params.sample_count = 1 + rng() % 200;
        request.params.filter_skip = FilterSkip(rng() % 3);
        request.params.small_nodes = SmallNodes(rng() % kSmallNodes.size());
        request.settings.width = 8 + int(rng() % 24);
        worker.set_paused(rng() % 10 == 0);
        id = worker.submit(request);
        if (rng() % 8 == 0) std::this_thread::sleep_for(std::chrono::microseconds(rng() % 2000));
        (void)worker.latest();
    }
    worker.set_paused(false);
    id = worker.submit(request);
    const auto frame = wait_for(worker, id, request.spp_target);
    ASSERT_TRUE(frame) << "the worker did not finish the last request";
    EXPECT_EQ(frame->error, "");
    EXPECT_EQ(frame->image.width, request.settings.width);
}

TEST(OrbitCamera, ResetReproducesTheCameraAndOrbitKeepsTheDistance) {
    OrbitCamera orbit;
    const Camera camera{{1, 2, 5}, {0, 1, 0}, {0, 1, 0}, 40.0f};
    orbit.reset(camera);
    const Camera again = orbit.camera();
    EXPECT_NEAR(again.eye.x, 1.0f, 1e-5f);
    EXPECT_NEAR(again.eye.y, 2.0f, 1e-5f);
    EXPECT_NEAR(again.eye.z, 5.0f, 1e-5f);
    orbit.orbit(120.0f, -40.0f);
    const Camera moved = orbit.camera();
    EXPECT_NEAR(glm::length(moved.eye - moved.look_at), glm::length(camera.eye - camera.look_at),
                1e-4f);
    EXPECT_NO_THROW(validate(moved));
    orbit.orbit(0.0f, 1e6f);  // pitch is clamped short of the pole
    EXPECT_NO_THROW(validate(orbit.camera()));
    orbit.zoom(3.0f);
    EXPECT_LT(glm::length(orbit.camera().eye - orbit.camera().look_at),
              glm::length(moved.eye - moved.look_at));
}

// Looking turns the view about the eye: the eye stays, the view direction turns as an orbit
// of the same drag turns it, and the opposite drag turns it back.
TEST(OrbitCamera, LookKeepsTheEyeAndTurnsTheView) {
    OrbitCamera orbit;
    const Camera camera{{1, 2, 5}, {0, 1, 0}, {0, 1, 0}, 40.0f};
    orbit.reset(camera);
    OrbitCamera orbiting = orbit;
    orbit.look(80.0f, 25.0f);
    orbiting.orbit(80.0f, 25.0f);
    const Camera looked = orbit.camera(), orbited = orbiting.camera();
    EXPECT_LT(glm::length(looked.eye - camera.eye), 1e-4f);
    const glm::vec3 turned = glm::normalize(looked.look_at - looked.eye);
    EXPECT_GT(glm::length(turned - glm::normalize(camera.look_at - camera.eye)), 0.3f);
    EXPECT_LT(glm::length(turned - glm::normalize(orbited.look_at - orbited.eye)), 1e-4f);
    orbit.look(-80.0f, -25.0f);
    EXPECT_LT(glm::length(orbit.camera().look_at - camera.look_at), 1e-4f);
}

// Orbiting about a point keeps the eye, looks at the point, and orbits at its distance.
TEST(OrbitCamera, OrbitAboutAPointKeepsTheEye) {
    OrbitCamera orbit;
    orbit.reset({{0, 1, 10}, {0, 1, -20}, {0, 1, 0}, 45.0f});
    const glm::vec3 point(1.0f, 0.5f, 6.0f);
    orbit.orbit_about(point);
    EXPECT_LT(glm::length(orbit.camera().eye - glm::vec3(0, 1, 10)), 1e-4f);
    EXPECT_LT(glm::length(orbit.camera().look_at - point), 1e-5f);
    orbit.orbit(200.0f, 30.0f);
    EXPECT_NEAR(glm::length(orbit.camera().eye - point), glm::length(glm::vec3(0, 1, 10) - point),
                1e-4f);
}

// Flight covers the scene in ten seconds at step 0 whatever its units; each step is 1.25x, and
// steps stop at +-kFlySpeedSteps. fly() moves eye and target by the distance given.
TEST(OrbitCamera, FlySpeedFollowsTheSceneSize) {
    const Aabb box{{0, 0, 0}, {30, 40, 0}};  // diagonal 50
    EXPECT_FLOAT_EQ(fly_speed(box, 0), 5.0f);
    const Aabb large{{0, 0, 0}, {3000, 4000, 0}};
    EXPECT_FLOAT_EQ(fly_speed(large, 0), 500.0f);
    EXPECT_FLOAT_EQ(fly_speed(box, 2), 5.0f * 1.25f * 1.25f);
    EXPECT_FLOAT_EQ(fly_speed(box, 1000), fly_speed(box, kFlySpeedSteps));
    EXPECT_GT(fly_speed(Aabb{}, 0), 0.0f);  // an empty scene still flies
    OrbitCamera orbit;
    orbit.reset({{0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 45.0f});
    orbit.fly(1.0f, 0.0f, 0.0f, 2.5f);
    EXPECT_NEAR(orbit.camera().eye.z, 7.5f, 1e-5f);
    EXPECT_NEAR(orbit.camera().look_at.z, -2.5f, 1e-5f);
}

// Left drags orbit from outside the scene's box and look from inside it, so no drag inside an
// interior swings the eye out through a wall; right drags look, middle and Shift+left pan.
TEST(OrbitCamera, DragsInsideTheSceneNeverMoveTheEyeOut) {
    EXPECT_EQ(drag_action(0, false, false), DragAction::orbit);
    EXPECT_EQ(drag_action(0, false, true), DragAction::look);
    EXPECT_EQ(drag_action(1, false, false), DragAction::look);
    EXPECT_EQ(drag_action(2, false, true), DragAction::pan);
    EXPECT_EQ(drag_action(0, true, true), DragAction::pan);
    // Sponza's default view: the eye inside, the look-at point on the far wall.
    const Aabb building{{-19.2f, -0.1f, -8.0f}, {18.0f, 15.4f, 7.2f}};
    OrbitCamera orbit;
    orbit.reset({{-10.0f, 2.0f, -0.3f}, {14.0f, 4.0f, 0.1f}, {0, 1, 0}, 60.0f});
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> pixels(-60.0f, 60.0f);
    for (int i = 0; i < 200; ++i) {
        const bool inside = building.contains(orbit.camera().eye);
        ASSERT_TRUE(inside) << "drag " << i;
        const float dx = pixels(rng), dy = pixels(rng);
        if (drag_action(0, false, inside) == DragAction::orbit)
            orbit.orbit(dx, dy);
        else
            orbit.look(dx, dy);
    }
}

// A double click orbits about the surface under the cursor: the camera ray's first hit.
TEST(OrbitCamera, OrbitAboutAPixelTakesTheSurfaceUnderIt) {
    ViewerState s;
    s.scene = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    const Aabb box = s.scene->bounds();
    const glm::vec3 centre = box.center();
    // From the open side, looking at the back wall's centre.
    s.camera.reset({centre + glm::vec3(0, 0, 3.0f * box.extent().z), centre, {0, 1, 0}, 40.0f});
    const glm::vec3 eye = s.camera.camera().eye;
    ASSERT_TRUE(orbit_about_pixel(s, 0.5f, 0.5f)) << s.status;
    EXPECT_LT(glm::length(s.camera.camera().eye - eye), 1e-3f);
    const glm::vec3 point = s.camera.camera().look_at;
    const Aabb near_box{box.lo - glm::vec3(1e-3f), box.hi + glm::vec3(1e-3f)};
    EXPECT_TRUE(near_box.contains(point));
    EXPECT_NE(s.status.find("orbiting about"), std::string::npos);
    // Looking away from the box: nothing there, and the view stays.
    s.camera.reset({centre + glm::vec3(0, 0, 3.0f * box.extent().z),
                    centre + glm::vec3(0, 0, 6.0f * box.extent().z),
                    {0, 1, 0},
                    40.0f});
    const Camera away = s.camera.camera();
    EXPECT_FALSE(orbit_about_pixel(s, 0.5f, 0.5f));
    EXPECT_EQ(s.camera.camera(), away);
    EXPECT_EQ(s.status, "nothing under the cursor to orbit about");
}

// The navigation verbs: look takes pixels, orbit-about fractions of the image; a script that
// looks around in the Cornell box keeps its eye, and orbit-about there names the point.
TEST(OrbitCamera, ScriptLooksAndOrbitsAboutAPoint) {
    EXPECT_EQ(parse_script("look 10 -5\norbit-about 0.5 0.25\n", "s")[1].numbers,
              (std::vector<double>{0.5, 0.25}));
    EXPECT_EQ(test::error_of([] { parse_script("orbit-about 2 0\n", "s"); }).rfind("s:1: ", 0), 0u);
    ViewerState s;
    s.scene = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    const Aabb box = s.scene->bounds();
    s.camera.reset(
        {box.center() + glm::vec3(0, 0, 3.0f * box.extent().z), box.center(), {0, 1, 0}, 40.0f});
    const glm::vec3 eye = s.camera.camera().eye;
    ScriptRunner runner(parse_script("look 5 2\norbit-about 0.5 0.5\nquit\n", "s"));
    bool quit = false;
    std::string screenshot;
    for (int frame = 0; frame < 10 && !quit; ++frame) runner.step(s, {}, screenshot, quit);
    EXPECT_TRUE(quit);
    EXPECT_LT(glm::length(s.camera.camera().eye - eye), 1e-3f);
    EXPECT_NE(s.status.find("orbiting about"), std::string::npos) << s.status;
}

TEST(HeatMap, ValuesComeFromThePerRayStatistics) {
    TraceDetail detail;
    detail.rays = {{3, 4, 5, 6}, {7, 8, 9, 10}};
    EXPECT_EQ(heat_values(detail.rays, View::box_tests), (std::vector<float>{3, 7}));
    EXPECT_EQ(heat_values(detail.rays, View::triangle_tests), (std::vector<float>{4, 8}));
    EXPECT_EQ(heat_values(detail.rays, View::depth), (std::vector<float>{5, 9}));
    EXPECT_EQ(heat_values(detail.rays, View::order_misses), (std::vector<float>{6, 10}));
    // Turbo runs from dark blue through green to dark red.
    EXPECT_GT(turbo(0.0f).z, turbo(0.0f).y);
    EXPECT_GT(turbo(0.5f).y, turbo(0.5f).z);
    EXPECT_GT(turbo(1.0f).x, 4.0f * turbo(1.0f).z);
}

TEST(Script, ParsesCommandsAndNamesTheLineOfAnError) {
    const auto commands =
        parse_script("# a comment\nset bins 16\n\nwait-spp 4 # more\nquit\n", "s");
    ASSERT_EQ(commands.size(), 3u);
    EXPECT_EQ(commands[0].verb, "set");
    EXPECT_EQ(commands[0].args, (std::vector<std::string>{"bins", "16"}));
    EXPECT_EQ(commands[1].line, 4);
    try {
        parse_script("view box\nfly away\n", "s.txt");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "s.txt:2: unknown script command 'fly'");
    }
    EXPECT_THROW(parse_script("set bins\n", "s"), InputError);
    EXPECT_THROW(load_script("/no/such/script"), InputError);
}

using test::error_of;

TEST(Script, NumberErrorsNameTheLineAndTheValue) {
    EXPECT_EQ(error_of([] { parse_script("quit\nwait-spp lots\n", "s"); }),
              "s:2: 'wait-spp' takes whole numbers from 0, got 'lots'");
    EXPECT_EQ(error_of([] { parse_script("frames -1\n", "s"); }),
              "s:1: 'frames' takes whole numbers from 0, got '-1'");
    EXPECT_EQ(error_of([] { parse_script("orbit 10 up\n", "s"); }),
              "s:1: 'orbit' takes numbers, got 'up'");
    EXPECT_EQ(error_of([] { parse_script("pick nan 3\n", "s"); }),
              "s:1: 'pick' takes numbers, got 'nan'");
    EXPECT_EQ(parse_script("orbit -2.5 1e1\n", "s")[0].numbers, (std::vector<double>{-2.5, 10.0}));
}

/// Runs `script` to its end (or its first error) against `state`, as the viewer does a frame
/// at a time with nothing rendered.
std::string run_script(ViewerState& state, const std::string& script) {
    ScriptRunner runner(parse_script(script, "s"));
    return error_of([&] {
        std::string screenshot;
        bool quit = false;
        for (int frame = 0; frame < 100 && runner.active() && !quit; ++frame) {
            runner.step(state, {}, screenshot, quit);
            state.save_requested = ViewerState::Save::none;  // "saved"
        }
    });
}

// The waiting verbs, `timeout`, `layout` and `pick-image` parse with their arguments checked.
TEST(Script, WaitsTimeoutLayoutAndPickImageParse) {
    const auto commands = parse_script(
        "wait-loaded\nwait-error\nwait-settled\ntimeout 2.5\nlayout out/l.json\n"
        "pick-image 0.5 1\n",
        "s");
    ASSERT_EQ(commands.size(), 6u);
    EXPECT_EQ(commands[2].verb, "wait-settled");
    EXPECT_EQ(commands[3].numbers, std::vector<double>{2.5});
    EXPECT_EQ(commands[4].args, std::vector<std::string>{"out/l.json"});
    EXPECT_EQ(commands[5].numbers, (std::vector<double>{0.5, 1.0}));
    // (A pair, not a structured binding: Clang 14 cannot capture those in a lambda.)
    for (const auto& c : std::vector<std::pair<std::string, std::string>>{
             {"wait-error now\n", "s:1: 'wait-error' takes 0 argument(s)"},
             {"wait-loaded x\n", "s:1: 'wait-loaded' takes 0 argument(s)"},
             {"quit\nwait-settled 3\n", "s:2: 'wait-settled' takes 0 argument(s)"},
             {"timeout 0\n",
              "s:1: 'timeout' takes seconds, more than 0 and at most 86400, got '0'"},
             {"timeout -1\n",
              "s:1: 'timeout' takes seconds, more than 0 and at most 86400, got '-1'"},
             {"timeout 1e9\n", "'timeout' takes seconds, more than 0 and at most 86400, got '1e9'"},
             {"timeout soon\n", "got 'soon'"},
             {"timeout\n", "s:1: 'timeout' takes 1 argument(s)"},
             {"layout\n", "s:1: 'layout' takes 1 argument(s)"},
             {"pick-image 0.5\n", "s:1: 'pick-image' takes 2 argument(s)"},
             {"pick-image 1.5 0\n", "s:1: 'pick-image' takes numbers from 0 to 1, got '1.5'"},
             {"pick-image 0 -0.1\n", "s:1: 'pick-image' takes numbers from 0 to 1, got '-0.1'"},
             {"pick-image nan 0\n", "got 'nan'"},
         })
        EXPECT_NE(error_of([&] { parse_script(c.first, "s"); }).find(c.second), std::string::npos)
            << c.first << ": " << error_of([&] { parse_script(c.first, "s"); });
}

// Every wait fails the script at its line once its timeout has passed, naming what it waited
// for; a condition that holds ends the wait at once.
TEST(Script, WaitsTimeOutWithAClearMessage) {
    for (const auto& [wait, what] : std::vector<std::pair<std::string, std::string>>{
             {"wait-spp 4", "4 spp"},
             {"wait-error", "an error message on screen"},
             {"wait-loaded", "the scene to load"},
             {"wait-settled", "the screen to settle"},
         }) {
        ViewerState s;
        ScriptRunner runner(parse_script("timeout 0.05\n" + wait + "\nquit\n", "s"));
        std::string screenshot;
        bool quit = false;
        runner.step(s, {}, screenshot, quit);
        EXPECT_TRUE(runner.active()) << wait;
        std::this_thread::sleep_for(std::chrono::milliseconds(80));
        const std::string error = error_of([&] { runner.step(s, {}, screenshot, quit); });
        EXPECT_EQ(error.rfind("script line 2: timed out after 0.05 s waiting for " + what, 0), 0u)
            << wait << ": " << error;
        EXPECT_FALSE(quit);
    }
    ViewerState s;
    s.errors_shown = {"a 1280x800 render needs more memory"};
    EXPECT_EQ(run_script(s, "timeout 0.05\nwait-error\n"), "");
}

// wait-error: an error drawn in the last frame, or with the panels hidden one they would show.
TEST(Script, WaitErrorWaitsForAnErrorOnScreen) {
    ViewerState s;
    std::string screenshot;
    bool quit = false;
    ScriptRunner runner(parse_script("wait-error\nquit\n", "s"));
    s.scene_error = "/no/such.obj: no such file";  // held, but the frame did not draw it
    runner.step(s, {}, screenshot, quit);
    EXPECT_FALSE(quit);
    s.errors_shown = {s.scene_error};  // drawn by the Scene tab
    runner.step(s, {}, screenshot, quit);
    EXPECT_TRUE(quit);

    ViewerState hidden;
    hidden.panels_hidden = true;
    hidden.resolution_error = "a 1280x800 path render needs about 346 MB";
    EXPECT_EQ(run_script(hidden, "wait-error\n"), "");
}

// wait-loaded: the scene asked for is loaded and its render asked for; a failed load fails the
// script with the loader's message.
TEST(Script, WaitLoadedFailsOnALoadError) {
    ViewerState s;
    std::string screenshot;
    bool quit = false;
    ScriptRunner runner(parse_script("set scene builtin:cornell\nwait-loaded\nquit\n", "s"));
    runner.step(s, {}, screenshot, quit);
    ASSERT_EQ(s.pending_loads, std::vector<std::string>{"builtin:cornell"});
    runner.step(s, {}, screenshot, quit);
    EXPECT_FALSE(quit) << "the load is still pending";
    load_into(s, "builtin:cornell");  // what the viewer does at the start of a frame
    s.pending_loads.clear();
    runner.step(s, {}, screenshot, quit);
    EXPECT_FALSE(quit) << "the render is not asked for yet";
    s.submitted.scene = s.scene;
    runner.step(s, {}, screenshot, quit);
    EXPECT_FALSE(quit) << "the tracer has not taken the scene yet";
    s.render_answered = true;
    runner.step(s, {}, screenshot, quit);
    EXPECT_TRUE(quit);

    // A method that refuses the scene (Embree past its range) fails the wait, as other waits.
    s.render_error = "Embree cannot trace far.obj: coordinates reach 1e+30";
    EXPECT_EQ(run_script(s, "wait-loaded\n"),
              "script line 1: the render failed: Embree cannot trace far.obj: coordinates reach "
              "1e+30");
    s.render_error.clear();

    s.scene_error = "/no/such/scene.obj: no such file";
    EXPECT_EQ(run_script(s, "wait-loaded\n"),
              "script line 1: the scene did not load: /no/such/scene.obj: no such file");
}

// wait-settled: the image shows the view asked for and the layout has not changed for three
// frames; a tab asked for and not yet drawn keeps it waiting.
TEST(Script, WaitSettledWaitsForAStillLayout) {
    ViewerState s;
    std::string screenshot;
    bool quit = false;
    ScriptRunner runner(parse_script("tab Statistics\nwait-settled\nquit\n", "s"));
    s.placements = {{"Controls", {0, 0, 300, 800}, 0, 1}};
    runner.step(s, {4, true}, screenshot, quit);  // frame 1
    EXPECT_EQ(s.select_tabs, std::vector<std::string>{"Statistics"});
    s.select_tabs.clear();                        // the panel brought it forward
    runner.step(s, {4, true}, screenshot, quit);  // frame 2: the same layout once
    s.placements[0].cell_widths = 2;              // columns fitting
    runner.step(s, {4, true}, screenshot, quit);
    runner.step(s, {4, true}, screenshot, quit);
    EXPECT_FALSE(quit);
    runner.step(s, {4, false}, screenshot, quit);  // a new pass not yet uploaded
    EXPECT_FALSE(quit);
    runner.step(s, {4, true}, screenshot, quit);  // three frames alike
    EXPECT_TRUE(quit);
}

// `layout FILE` writes the last frame's regions, panels and reported widgets; pick-image
// picks at a fraction of the image region.
TEST(Script, LayoutWritesTheFramesRectanglesAndPickImageUsesTheImageRegion) {
    const test::TempDir dir;
    ViewerState s;
    s.window_width = 1280;
    s.window_height = 800;
    s.layout = compute_layout({1280, 800, 13, 19, false, true, false});
    s.placements = {{"Controls", s.layout.controls, 0, 7}};
    s.items = {{"Scene/scenes", {8, 60, 335, 19}}};
    s.tabs_open = {"Scene"};
    const auto file = dir.path() / "new" / "layout.json";
    ScriptRunner runner(parse_script("layout " + file.string() + "\npick-image 0.5 1\n", "s"));
    std::string screenshot;
    bool quit = false;
    runner.step(s, {}, screenshot, quit);
    const auto json = nlohmann::json::parse(std::ifstream(file));
    EXPECT_EQ(json["window"]["w"], 1280);
    EXPECT_EQ(json["framebuffer_scale"]["x"], 1);
    EXPECT_EQ(json["image"]["x"], s.layout.image.x);
    EXPECT_EQ(json["image"]["w"], s.layout.image.w);
    EXPECT_EQ(json["panels"]["Controls"]["h"], 800);
    EXPECT_EQ(json["panels"]["Controls"]["clipped_cells"], 0);
    EXPECT_EQ(json["items"]["Scene/scenes"]["y"], 60);
    EXPECT_EQ(json["tabs_open"], nlohmann::json::array({"Scene"}));
    const auto pick = runner.take_pick();
    ASSERT_TRUE(pick);
    EXPECT_EQ(pick->x, s.layout.image.x + 0.5f * s.layout.image.w);
    EXPECT_EQ(pick->y, s.layout.image.bottom() - 0.5f) << "inside the region";
    EXPECT_NE(run_script(s, "layout " + dir.path().string() + "\n").find("script line 1: "),
              std::string::npos)
        << "a folder is not a layout file";
}

// Every verb is described once (script_verbs()): the parser takes it with its argument count,
// --script-help lists it with its arguments, and the README names it.
TEST(Script, EveryVerbParsesAndIsInTheHelpAndTheReadme) {
    std::ifstream file(std::string(EDACRT_SOURCE_DIR) + "/README.md");
    const std::string readme(std::istreambuf_iterator<char>(file), {});
    const std::string help = script_help();
    std::set<std::string_view> names;
    for (const ScriptVerb& verb : script_verbs()) {
        EXPECT_TRUE(names.insert(verb.name).second) << verb.name << " twice";
        EXPECT_TRUE(verb.run) << verb.name;
        EXPECT_FALSE(verb.help.empty()) << verb.name;
        std::string line(verb.name);
        const char* arg = verb.kind == ScriptArgs::fraction ? "0.5" : "1";
        for (std::size_t i = 0; i < verb.args; ++i) line += std::string(" ") + arg;
        EXPECT_EQ(error_of([&] { parse_script(line + "\n", "s"); }), "") << line;
        EXPECT_NE(error_of([&] { parse_script(line + " 1 2\n", "s"); }), "") << line;
        const std::string usage = "  " + std::string(verb.name) +
                                  (verb.usage.empty() ? "" : " " + std::string(verb.usage));
        EXPECT_NE(help.find(usage), std::string::npos) << usage;
        const std::string quoted = std::string("`").append(verb.name);
        EXPECT_NE(readme.find(quoted), std::string::npos) << verb.name << " is not in README.md";
    }
}

// `set` checks what the widgets allow, from the same table (viewer_settings(), whose ranges
// are the renderer's), and names the script line.
TEST(Script, SetValuesAreRangeChecked) {
    ViewerState s;
    for (const auto& [line, message] : std::vector<std::pair<std::string, std::string>>{
             {"set spp -5", "script line 1: spp must be a whole number from 1 to 1048576, got -5"},
             {"set spp 2.5", "spp must be a whole number"},
             {"set threads -1", "threads must be a whole number from 0 to 1024, got -1"},
             {"set resolution -0.5", "resolution must be from 0.125 to 1, got -0.5"},
             {"set resolution 4", "resolution must be from 0.125 to 1, got 4"},
             {"set seed -1", "seed must be a whole number from 0"},
             {"set max-depth -1",
              "script line 1: max-depth must be a whole number from 0 to 1024, got -1"},
             {"set ao-samples 1e12", "ao-samples must be a whole number from 1 to 1024"},
             {"set spp x", "script line 1: 'spp' needs a number, got 'x'"},
         }) {
        const std::string error = run_script(s, line + "\n");
        EXPECT_NE(error.find(message), std::string::npos) << line << ": " << error;
    }
    EXPECT_EQ(s.ui, UiSettings{}) << "nothing out of range was taken";
    EXPECT_EQ(run_script(s, "set spp 64\nset threads 2\nset resolution 0.5\nset max-depth 3\n"),
              "");
    EXPECT_EQ(s.ui.spp_target, 64);
    EXPECT_EQ(s.ui.threads, 2);
    EXPECT_EQ(s.ui.resolution_scale, 0.5f);
    EXPECT_EQ(s.ui.max_depth, 3);
}

// A save or write the script asked for that fails, fails the script at its line; a render that
// failed ends a wait with its error instead of waiting five minutes.
TEST(Script, FailedSavesAndRenderErrorsFailTheScript) {
    ViewerState s;
    ScriptRunner runner(parse_script("frames 0\nsave-linear /x.pfm\n", "s"));
    std::string screenshot;
    bool quit = false;
    runner.step(s, {}, screenshot, quit);
    EXPECT_EQ(s.save_requested, ViewerState::Save::linear);
    EXPECT_TRUE(runner.active()) << "the outcome of the save is still to check";
    s.save_requested = ViewerState::Save::none;  // what the viewer does on a failed save
    s.save_error = "/x.pfm: cannot create PFM";
    EXPECT_EQ(error_of([&] { runner.step(s, {}, screenshot, quit); }),
              "script line 2: /x.pfm: cannot create PFM");

    EXPECT_NE(run_script(s, "write-command /dev/full\n")
                  .find("script line 1: /dev/full: cannot write command line"),
              std::string::npos);
    s.render_error = "c-i (C_I) must be positive";
    for (const char* wait : {"wait-spp 4", "wait-analysis", "wait-compare"}) {
        const std::string script = std::string("record\ncompare\n") + wait + "\n";
        EXPECT_EQ(run_script(s, script),
                  "script line 3: the render failed: c-i (C_I) must be positive")
            << wait;
    }
}

// Every change keeps the camera finite and valid: one beyond float range is refused with a
// message and the camera stays as it was (a NaN view once stalled the render and was written
// out by write-command and bookmark).
TEST(OrbitCamera, ChangesBeyondFloatRangeAreRefusedAndKeepTheCamera) {
    OrbitCamera orbit;
    orbit.reset({{1, 2, 5}, {0, 1, 0}, {0, 1, 0}, 40.0f});
    const Camera before = orbit.camera();
    const float huge = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<std::pair<std::string, std::function<void()>>> changes = {
        {"orbit", [&] { orbit.orbit(huge, huge); }},
        {"orbit", [&] { orbit.orbit(nan, 0.0f); }},
        {"pan", [&] { orbit.pan(3e38f, -3e38f, 1.0f); }},
        {"zoom", [&] { orbit.zoom(-1e4f); }},
        {"zoom", [&] { orbit.zoom(nan); }},
        {"fly", [&] { orbit.fly(1.0f, 0.0f, 0.0f, huge); }},
        {"fly", [&] { orbit.fly(1.0f, 1.0f, 0.0f, 3e38f); }},
        {"look", [&] { orbit.look(nan, 1.0f); }},
        {"view", [&] { orbit.orbit_about(before.eye); }},
        {"view",
         [&] {
             orbit.reset({{3e38f, 0, 0}, {-3e38f, 0, 0}, {0, 1, 0}, 45.0f});
         }},
        {"view",
         [&] {
             orbit.reset({{nan, 0, 0}, {0, 0, 0}, {0, 1, 0}, 45.0f});
         }},
    };
    for (const auto& [what, change] : changes) {
        const std::string error = error_of(change);
        EXPECT_EQ(error.rfind(what + " refused, the view is unchanged: camera", 0), 0u)
            << what << ": " << error;
        EXPECT_EQ(orbit.camera(), before) << what;
    }
    EXPECT_NO_THROW(orbit.orbit(1e3f, 0.0f));  // an ordinary change is taken
    EXPECT_NE(orbit.camera(), before);
    EXPECT_NO_THROW(validate(orbit.camera()));
}

// A script's orbit beyond float range fails its line with the camera's message, which the
// status line shows; the view, and what write-command and bookmark write, stay finite.
TEST(Script, AnOrbitBeyondFloatRangeFailsAndKeepsTheView) {
    const test::TempDir dir;
    ViewerState s;
    s.scene_path = "builtin:sphere";
    s.camera.reset({{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 45.0f});
    const Camera before = s.camera.camera();
    s.bookmarks_path = (dir.path() / "bookmarks.json").string();
    EXPECT_EQ(run_script(s, "frames 0\norbit 1e40 1e40\n"),
              "script line 2: orbit refused, the view is unchanged: camera: eye, look-at and up "
              "must be finite");
    EXPECT_EQ(s.status,
              "orbit refused, the view is unchanged: camera: eye, look-at and up must be finite");
    EXPECT_EQ(s.camera.camera(), before);
    EXPECT_EQ(run_script(s, "bookmark after\n"), "");
    Bookmarks read;
    EXPECT_TRUE(read.load(s.bookmarks_path).empty());
    ASSERT_EQ(read.of("builtin:sphere").size(), 1u);
    EXPECT_EQ(read.of("builtin:sphere")[0].camera, before);
}

// `bookmark NAME` saves the view as the Camera tab's "save view" does: the file read back
// holds it; a file that cannot be written fails the script at its line.
TEST(Script, BookmarkSavesTheViewToTheBookmarksFile) {
    const test::TempDir dir;
    ViewerState s;
    s.scene_path = "builtin:cornell";
    const Camera view{{1.0f, 2.0f, 3.0f}, {0.0f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f}, 40.0f};
    s.camera.reset(view);
    s.bookmarks_path = (dir.path() / "config" / "bookmarks.json").string();
    EXPECT_EQ(run_script(s, "frames 0\nbookmark front\n"), "");
    Bookmarks read;
    EXPECT_TRUE(read.load(s.bookmarks_path).empty());
    const std::vector<Bookmark>& saved = read.of("builtin:cornell");
    ASSERT_EQ(saved.size(), 1u);
    EXPECT_EQ(saved[0].name, "front");
    EXPECT_EQ(saved[0].camera, s.camera.camera());
    EXPECT_NE(s.status.find("bookmarks saved to " + s.bookmarks_path), std::string::npos);

    s.bookmarks_path = dir.path().string();  // a folder, not a file
    EXPECT_EQ(run_script(s, "frames 0\nbookmark side\n")
                  .rfind("script line 2: bookmarks not saved: " + dir.path().string(), 0),
              0u);
    s.bookmarks_path.clear();  // neither XDG_CONFIG_HOME nor HOME
    EXPECT_EQ(run_script(s, "bookmark side\n"),
              "script line 1: bookmarks not saved: neither XDG_CONFIG_HOME nor HOME is set");
    EXPECT_THROW(parse_script("bookmark\n", "s"), InputError);
}

}  // namespace
// The script's view names (view NAME) are the table's; the heat map tab shows their help.
// The comparison's rays: the pixel centres at 1 spp, else the jittered sets of `edacrt bench`,
// all in one batch; refused with the figures when they cannot fit.
TEST(CompareMethods, ManyRaysPerPixelAreBenchsJitteredCameraRays) {
    const auto scene = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    const Camera camera = *scene->camera;
    const PinholeProjection projection(camera, 12, 8);
    const auto same = [](const std::vector<Ray>& a, const std::vector<Ray>& b) {
        return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Ray)) == 0;
    };
    EXPECT_TRUE(same(compare_rays(camera, 12, 8, 1, 3), projection.pixel_centre_rays()));
    for (const int spp : {4, 16}) {
        const std::vector<Ray> rays = compare_rays(camera, 12, 8, spp, 3);
        EXPECT_EQ(rays.size(), std::size_t(12 * 8 * spp));
        EXPECT_TRUE(same(rays, jittered_camera_rays(projection, 12, 8, spp, 3)));
        EXPECT_FALSE(same(rays, compare_rays(camera, 12, 8, spp, 4))) << "another seed";
    }
    RenderWorker idle;
    for (const MethodTotals& m :
         compare_methods(scene, nullptr, camera, 12, 8, 4, 0, EdacrtParams{}, &idle)) {
        EXPECT_EQ(m.error, "") << enum_name(kMethods, m.method);
        EXPECT_EQ(m.spp, 4);
        EXPECT_EQ(m.stats.rays, 12u * 8u * 4u);
    }
    ::setenv("EDACRT_MEMORY_LIMIT", "100000", 1);
    EXPECT_THROW(compare_rays(camera, 100, 100, 16, 0), InputError);
    const auto refused = compare_methods(scene, nullptr, camera, 100, 100, 16, 0, {}, &idle);
    ::unsetenv("EDACRT_MEMORY_LIMIT");
    ASSERT_FALSE(refused.empty());
    for (const MethodTotals& m : refused)
        EXPECT_NE(m.error.find("160000 rays (16 per pixel) need about"), std::string::npos)
            << m.error;
    ViewerState s;
    EXPECT_EQ(run_script(s, "set compare-spp 16\n"), "");
    EXPECT_EQ(s.compare_spp, 16);
    EXPECT_NE(run_script(s, "set compare-spp 3\n").find("'compare-spp' is 1, 4 or 16, got '3'"),
              std::string::npos);
    EXPECT_EQ(s.compare_spp, 16);
}

// The EDACRT panel greys what cannot change the render: param_no_effect_reason() for the
// method's parameters, everything for a method without them, dacrt's own choices for dacrt.
TEST(ParamsPanel, InertParametersFollowMethodSwitchesAndThreads) {
    const auto inert = [](const UiSettings& ui, const char* key) {
        return !param_inert_reason(ui, *find_param(key)).empty();
    };
    UiSettings ui;
    ui.threads = 2;
    EXPECT_TRUE(inert(ui, "c-t"));
    EXPECT_TRUE(inert(ui, "c-child"));
    EXPECT_FALSE(inert(ui, "c-i"));
    EXPECT_FALSE(inert(ui, "second-child"));
    EXPECT_FALSE(inert(ui, "hit-ratio"));
    ui.threads = 1;
    EXPECT_TRUE(inert(ui, "second-child"));
    ui.params.cost_leaf_max_tris = 64;
    EXPECT_FALSE(inert(ui, "c-t"));
    ui.method = Method::dacrt;
    for (const char* key : {"hit-ratio", "order", "filter-skip", "sample-count", "c-bv"})
        EXPECT_TRUE(inert(ui, key)) << key;
    EXPECT_FALSE(inert(ui, "bins"));
    ui.method = Method::bvh;
    for (const ParamInfo& info : edacrt_param_info())
        EXPECT_NE(param_inert_reason(ui, info), "") << info.key;
}

TEST(ViewNames, RoundTripAndRefuseUnknownNames) {
    test::expect_enum_table(kViews);
    EXPECT_EQ(parse_enum_or_throw(kViews, "box"), View::box_tests);
}

}  // namespace edacrt::app
