// The viewer's animation parts without a window: the frame pool shared across threads, the
// timeline's seek and playback rules, the render worker on an animation (refit frames equal
// rebuilt ones, motion blur is the average of the shutter's passes), the comparison's update
// variants and the command line of an animated view.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "command_line.h"
#include "frame_pool.h"
#include "render/renderer.h"
#include "render/sampler.h"
#include "render_worker.h"
#include "scene/builtin_scenes.h"
#include "util/error.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

constexpr const char* kWave = "wave:amplitude=0.08,wavelength=0.5,period=2";

std::shared_ptr<FramePool> wave_pool() {
    return std::make_shared<FramePool>(load_animated_scene("builtin:cornell", kWave));
}

/// Animation::frame(t) into a fresh copy of time 0.
Scene fresh_frame(double t) {
    AnimatedScene a = load_animated_scene("builtin:cornell", kWave);
    a.animation->frame(t, a.scene);
    return a.scene;
}

TEST(FramePool, SnapshotsEqualTheAnimationsFramesWhateverBufferTheyReuse) {
    FramePool pool(load_animated_scene("builtin:cornell", kWave));
    EXPECT_EQ(pool.duration(), 2.0);
    // Many times, through recycled buffers: each equals a frame written into a fresh copy.
    for (double t : {0.0, 0.7, 1.3, 0.7, 1.999, 0.25}) {
        const auto scene = pool.at(t);
        const Scene expected = fresh_frame(t);
        EXPECT_TRUE(scene->positions == expected.positions) << t;
        EXPECT_TRUE(scene->normals == expected.normals) << t;
        EXPECT_TRUE(scene->triangles == expected.triangles) << t;
    }
    EXPECT_EQ(pool.buffers(), 1u) << "one holder at a time: one buffer, reused";
    // Held snapshots are never rewritten; the same time while held is the same snapshot.
    const auto a = pool.at(0.5), b = pool.at(1.5), again = pool.at(1.5);
    EXPECT_EQ(b, again);
    EXPECT_NE(a, b);
    EXPECT_TRUE(a->positions == fresh_frame(0.5).positions);
    EXPECT_EQ(pool.buffers(), 2u);
    EXPECT_THROW(pool.at(std::nan("")), InputError);
    EXPECT_TRUE(pool.at(0.25)->positions == fresh_frame(0.25).positions)
        << "a failed frame leaves nothing wrong behind";
    EXPECT_THROW(FramePool(load_animated_scene("builtin:cornell", "")), std::invalid_argument);
}

TEST(FramePool, ThreadsShareSnapshotsAndBuffersStayFew) {
    const auto pool = wave_pool();
    std::vector<std::thread> threads;
    std::atomic<int> wrong{0};
    for (int k = 0; k < 3; ++k)
        threads.emplace_back([&, k] {
            for (int i = 0; i < 40; ++i) {
                const double t = 0.05 * double((i * 7 + k) % 40);
                const auto scene = pool->at(t);
                // The snapshot stays the frame of t while this thread holds it.
                const Scene expected = fresh_frame(t);
                if (!(scene->positions == expected.positions)) ++wrong;
            }
        });
    for (auto& t : threads) t.join();
    EXPECT_EQ(wrong, 0);
    EXPECT_LE(pool->buffers(), 4u) << "at most one per holder (three threads, one `last`)";
}

TEST(Playback, SeekWrapsWhenLoopingAndStopsAtTheEndOtherwise) {
    ViewerState s;
    load_into(s, "builtin:cornell", {}, kWave);
    ASSERT_TRUE(s.playback.frames) << s.scene_error;
    seek(s, 2.5);
    EXPECT_DOUBLE_EQ(s.playback.time, 0.5);
    EXPECT_TRUE(s.scene->positions == fresh_frame(0.5).positions);
    seek(s, -0.25);
    EXPECT_DOUBLE_EQ(s.playback.time, 1.75);
    s.playback.loop = false;
    s.playback.playing = true;
    seek(s, 7.0);
    EXPECT_DOUBLE_EQ(s.playback.time, 2.0);
    EXPECT_FALSE(s.playback.playing) << "the end stops playback without a loop";
    seek(s, -1.0);
    EXPECT_DOUBLE_EQ(s.playback.time, 0.0);
    // Play at the end without a loop starts over; with a loop the end is shown, not wrapped.
    seek(s, 2.0);
    toggle_play(s);
    EXPECT_TRUE(s.playback.playing);
    EXPECT_DOUBLE_EQ(s.playback.time, 0.0);
    toggle_play(s);
    EXPECT_FALSE(s.playback.playing);
    s.playback.loop = true;
    seek(s, 2.0);
    EXPECT_DOUBLE_EQ(s.playback.time, 2.0);
    seek(s, 4.5);
    EXPECT_DOUBLE_EQ(s.playback.time, 0.5);
    // A non-finite time is ignored; the scene stays.
    const auto scene = s.scene;
    seek(s, std::nan(""));
    EXPECT_EQ(s.scene, scene);
}

TEST(Playback, AdvancesOnlyOnceTheFrameIsShownByTheWallClockTimesTheSpeed) {
    ViewerState s;
    load_into(s, "builtin:cornell", {}, kWave);
    s.playback.speed = 0.5f;
    advance_playback(s, true, 0.3);
    EXPECT_EQ(s.playback.time, 0.0) << "paused: nothing moves";
    s.playback.playing = true;
    advance_playback(s, false, 0.2);
    advance_playback(s, false, 0.2);
    EXPECT_EQ(s.playback.time, 0.0) << "the frame is not shown yet";
    advance_playback(s, true, 0.2);
    EXPECT_NEAR(s.playback.time, 0.3, 1e-12) << "0.6 s waited at half speed";
    EXPECT_TRUE(s.scene->positions == fresh_frame(s.playback.time).positions);
    // Time the render is held (methods compared, or paused) does not count.
    s.comparing = true;
    advance_playback(s, false, 5.0);
    s.comparing = false;
    advance_playback(s, true, 0.2);
    EXPECT_NEAR(s.playback.time, 0.4, 1e-12);
    // The history keeps the first full pass of each request, with its method.
    Frame frame;
    frame.spp = 1;
    frame.time = 0.3;
    frame.update = {UpdateWork::refitted, 0.002};
    frame.first_pass_seconds = 0.05;
    record_frame_time(s, frame, Method::bvh);
    frame.spp = 5;
    record_frame_time(s, frame, Method::bvh);  // a later pass: not a new frame
    frame.spp = 1;
    record_frame_time(s, frame, Method::bvh);  // the same time seen from elsewhere
    ASSERT_EQ(s.playback.history.size(), 1u);
    EXPECT_EQ(s.playback.history[0].work, UpdateWork::refitted);
    EXPECT_EQ(s.playback.history[0].method, Method::bvh);
    for (int i = 0; i < 700; ++i) {
        frame.time = 0.001 * i;
        record_frame_time(s, frame, Method::edacrt);
    }
    EXPECT_EQ(s.playback.history.size(), Playback::kHistory);
    // A still scene neither plays nor records.
    load_into(s, "builtin:cornell");
    EXPECT_FALSE(s.playback.frames);
    EXPECT_FALSE(s.playback.playing);
    EXPECT_TRUE(s.playback.history.empty());
}

TEST(Playback, LoadingAnimationsAndBadSpecs) {
    ViewerState s;
    load_into(s, "builtin:cornell", {}, "wave:bogus=1");
    EXPECT_FALSE(s.scene) << "a bad spec loads nothing";
    EXPECT_NE(s.scene_error.find("bogus"), std::string::npos) << s.scene_error;
    load_into(s, "builtin:cornell");
    const Camera camera = s.camera.camera();
    s.camera.orbit(30.0f, 10.0f);
    const Camera moved = s.camera.camera();
    load_into(s, s.scene_path, {}, "twist", true);
    ASSERT_TRUE(s.playback.frames) << s.scene_error;
    EXPECT_EQ(s.camera.camera().eye, moved.eye) << "a new animation keeps the view";
    EXPECT_NE(s.camera.camera().eye, camera.eye);
    EXPECT_EQ(s.animation_field, s.playback.frames->spec());
    // The viewer's `set` keys drive the timeline; they need an animation.
    apply_setting(s, "time", "0.75");
    EXPECT_DOUBLE_EQ(s.playback.time, 0.75);
    apply_setting(s, "update", "dynamic");
    EXPECT_EQ(s.playback.update, SceneUpdate::dynamic);
    apply_setting(s, "shutter", "0.1");
    EXPECT_TRUE(s.playback.motion_blur);
    EXPECT_THROW(apply_setting(s, "speed", "100"), InputError);
    EXPECT_THROW(apply_setting(s, "play-scale", "3"), InputError);
    EXPECT_THROW(apply_setting(s, "update", "sometimes"), InputError);
    EXPECT_THROW(apply_setting(s, "time", "nan"), InputError);
    load_into(s, "builtin:cornell");
    EXPECT_THROW(apply_setting(s, "time", "1"), InputError);
    EXPECT_THROW(apply_setting(s, "animate", "explode:distance=-inf"), InputError);
}

RenderRequest animated_request(const std::shared_ptr<FramePool>& pool, double t, Method method) {
    RenderRequest r;
    r.animation = pool;
    r.time = t;
    r.scene = pool->at(t);
    r.camera = *r.scene->camera;
    r.method = method;
    r.update = SceneUpdate::refit;
    r.settings.width = 32;
    r.settings.height = 24;
    r.settings.max_depth = 3;
    r.spp_target = 2;
    r.preview_scale = 1;
    r.threads = 1;
    return r;
}

constexpr std::chrono::minutes kTimeout(1);

std::shared_ptr<const Frame> finished(const RenderWorker& worker, std::uint64_t id) {
    EXPECT_TRUE(worker.wait_idle(kTimeout));
    auto frame = worker.latest();
    EXPECT_TRUE(frame && frame->request == id);
    return frame;
}

/// The methods with a structure to refit, and edacrt; Embree where the build has it.
std::vector<Method> refit_methods() {
#ifdef EDACRT_HAS_EMBREE
    return {Method::bvh, Method::embree, Method::edacrt};
#else
    return {Method::bvh, Method::edacrt};
#endif
}

TEST(RenderWorker, AnimationFramesAreRefittedAndRenderAsIfRebuilt) {
    for (Method method : refit_methods()) {
        SCOPED_TRACE(std::string(enum_name(kMethods, method)));
        const auto pool = wave_pool();
        RenderWorker worker;
        auto first = finished(worker, worker.submit(animated_request(pool, 0.2, method)));
        ASSERT_TRUE(first);
        EXPECT_EQ(first->update.work,
                  method == Method::edacrt ? UpdateWork::none : UpdateWork::rebuilt);
        const auto refitted = finished(worker, worker.submit(animated_request(pool, 0.9, method)));
        ASSERT_TRUE(refitted);
        EXPECT_EQ(refitted->error, "");
        EXPECT_EQ(refitted->time, 0.9);
        EXPECT_EQ(refitted->update.work,
                  method == Method::edacrt ? UpdateWork::none : UpdateWork::refitted);
        EXPECT_GT(refitted->first_pass_seconds, 0.0);
        // The same frame as a still scene, built from scratch.
        RenderWorker still;
        RenderRequest r = animated_request(pool, 0.9, method);
        r.animation = nullptr;
        r.scene = std::make_shared<const Scene>(fresh_frame(0.9));
        const auto rebuilt = finished(still, still.submit(r));
        ASSERT_TRUE(rebuilt);
        EXPECT_TRUE(refitted->image.pixels == rebuilt->image.pixels);
        EXPECT_FALSE(refitted->image.pixels == first->image.pixels) << "the wave moved";
    }
}

TEST(RenderWorker, MotionBlurAveragesPassesOverTheShutter) {
    const auto pool = wave_pool();
    RenderWorker worker;
    RenderRequest request = animated_request(pool, 1.0, Method::edacrt);
    request.shutter = 0.5;
    request.spp_target = 4;
    request.settings.samples_per_pass = 4;  // a shutter still renders one sample per pass
    const auto blurred = finished(worker, worker.submit(request));
    ASSERT_TRUE(blurred);
    EXPECT_EQ(blurred->spp, 4);
    // The same by hand: sample k on the geometry of shutter_time(1, 0.5, k), which stratifies
    // the shutter: 1, 0.75, 0.875, 0.8125 + a quarter... (the radical inverse, shifted).
    const auto tracer = make_tracer(Method::edacrt, request.params);
    std::vector<Scene> frames;
    std::vector<double> times;
    for (std::uint32_t k = 0; k < 4; ++k) {
        times.push_back(shutter_time(1.0, 0.5, k));
        frames.push_back(fresh_frame(times.back()));
    }
    EXPECT_EQ(times[0], 1.0);
    std::sort(times.begin(), times.end());
    for (std::size_t k = 0; k < 4; ++k)  // one in each quarter of [0.75, 1.25)
        EXPECT_TRUE(times[k] >= 0.75 + 0.125 * double(k) && times[k] < 0.875 + 0.125 * double(k))
            << times[k];
    tracer->set_scene(frames[0]);
    Renderer renderer(frames[0], *tracer, request.camera, request.settings);
    for (std::size_t k = 0; k < 4; ++k) {
        tracer->update_scene(frames[k], SceneUpdate::rebuild);
        renderer.scene_changed(frames[k], true);
        renderer.render_pass(nullptr, nullptr, 1);
    }
    EXPECT_TRUE(blurred->image.pixels == renderer.film().mean().pixels);
    // Without the shutter, every sample is at t: another image.
    request.shutter = 0.0;
    const auto sharp = finished(worker, worker.submit(request));
    EXPECT_FALSE(sharp->image.pixels == blurred->image.pixels);
}

TEST(CompareMethods, AnAnimationFrameAlsoComparesRefitAndDynamicUpdates) {
    const auto pool = wave_pool();
    RenderWorker idle;
    const auto scene = pool->at(0.5);
    const auto rows =
        compare_methods(scene, pool->at(0.45), *scene->camera, 24, 16, 1, 0, EdacrtParams{}, &idle);
    std::vector<std::pair<Method, SceneUpdate>> seen;
    for (const MethodTotals& m : rows) {
        seen.emplace_back(m.method, m.update);
#ifndef EDACRT_HAS_EMBREE
        if (m.method == Method::embree) {  // a row that says why
            EXPECT_NE(m.error.find("no Embree"), std::string::npos) << m.error;
            continue;
        }
#endif
        EXPECT_EQ(m.error, "") << enum_name(kMethods, m.method);
        EXPECT_EQ(m.stats.rays, 24u * 16u);
        EXPECT_GT(m.seconds, 0.0);
        EXPECT_LE(m.update_seconds, m.seconds);
    }
    for (const auto& expected : {std::pair(Method::bvh, SceneUpdate::refit),
                                 std::pair(Method::embree, SceneUpdate::dynamic),
                                 std::pair(Method::embree, SceneUpdate::refit),
                                 std::pair(Method::edacrt, SceneUpdate::rebuild)})
        EXPECT_NE(std::find(seen.begin(), seen.end(), expected), seen.end());
    // A still scene: one row per method.
    EXPECT_EQ(
        compare_methods(scene, nullptr, *scene->camera, 8, 8, 1, 0, EdacrtParams{}, &idle).size(),
        5u);
}

TEST(CommandLine, AnAnimatedViewNamesItsAnimationTimeAndShutter) {
    ViewCommand v;
    v.scene = "builtin:cornell";
    v.animated = true;
    v.animation = kWave;
    v.time = 0.1 + 0.2;  // not a short decimal: printed to read back exactly
    v.update = SceneUpdate::dynamic;
    v.shutter = 0.04;
    const std::string line = render_command_line(v);
    EXPECT_NE(line.find("--scene builtin:cornell --animate " + std::string(kWave)),
              std::string::npos)
        << line;
    EXPECT_NE(line.find("--time 0.30000000000000004"), std::string::npos) << line;
    EXPECT_NE(line.find("--update dynamic --shutter 0.040000000000000001"), std::string::npos)
        << line;
    v.scene = "assets/animations/spot-and-teapot.anim.json";
    v.animation.clear();
    v.shutter = 0.0;
    const std::string file = render_command_line(v);
    EXPECT_NE(file.find("edacrt render --animate " + (std::filesystem::current_path() /
                                                      "assets/animations/spot-and-teapot.anim.json")
                                                         .string()),
              std::string::npos)
        << file;
    EXPECT_EQ(file.find("--scene"), std::string::npos);
    EXPECT_EQ(file.find("--shutter"), std::string::npos);
}

}  // namespace
}  // namespace edacrt::app
