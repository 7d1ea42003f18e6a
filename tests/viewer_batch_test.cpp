// The analysis of any batch of the first pass (ViewerState::batch): what the analysis job
// records for camera, bounce, shadow and AO rays, the crop and the followed pixel, when a
// recording is stale, what the tabs show, `set batch` and `write-analysis`.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <numeric>

#include "input_error.h"
#include "render/batch_capture.h"
#include "scene/builtin_scenes.h"
#include "script_runner.h"
#include "trace/naive_tracer.h"
#include "util/error.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

using Kind = BatchId::Kind;

std::shared_ptr<const Scene> cornell() {
    static const auto scene = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    return scene;
}

RenderRequest request(int width, int height, Integrator integrator = Integrator::path) {
    RenderRequest r;
    r.scene = cornell();
    r.camera = *r.scene->camera;
    r.settings.width = width;
    r.settings.height = height;
    r.settings.integrator = integrator;
    r.settings.max_depth = 3;
    r.settings.ao_samples = 2;
    r.settings.samples_per_pass = 4;  // as the viewer asks: the batch is of one sample still
    r.settings.wavefront_paths = 100;
    return r;
}

std::uint64_t box_tests(std::span<const RayStats> rays) {
    std::uint64_t n = 0;
    for (const RayStats& r : rays) n += r.ray_box_tests;
    return n;
}

TEST(AnalyseBatch, EveryBatchOfThePassIsRecordedWithItsPixels) {
    for (const Integrator integrator : {Integrator::path, Integrator::ao}) {
        const RenderRequest r = request(24, 16, integrator);
        NaiveTracer naive;
        naive.set_scene(*r.scene);
        RenderSettings one = r.settings;
        for (const BatchId b : pass_batches(r.settings)) {
            SCOPED_TRACE(batch_name(b));
            const auto a = analyse(r, -1, false, {}, b);
            ASSERT_EQ(a->error, "");
            ASSERT_TRUE(a->detail);
            EXPECT_EQ(a->batch, b);
            EXPECT_EQ(a->settings, r.settings);
            ASSERT_EQ(a->pixels.size(), a->detail->rays.size());
            // The renderer's batch (taken with another tracer: the same rays), pixel for pixel.
            const CapturedBatch c = capture_batch(*r.scene, naive, r.camera, one, b);
            EXPECT_EQ(a->pixels, c.pixels);
            if (b == BatchId{}) {
                std::vector<std::uint32_t> all(24 * 16);
                std::iota(all.begin(), all.end(), 0u);
                EXPECT_EQ(a->pixels, all);
            }
            // Per pixel, the batch's counts summed.
            ASSERT_EQ(a->pixel_stats.size(), 24u * 16u);
            EXPECT_EQ(box_tests(a->pixel_stats), box_tests(a->detail->rays));
            EXPECT_GT(box_tests(a->pixel_stats), 0u);
        }
    }
}

TEST(AnalyseBatch, TheCropKeepsItsRaysAndThePixelIsFollowedInsideIt) {
    const RenderRequest r = request(100, 80);
    const BatchId bounce{Kind::bounce, 1};
    const std::int64_t centre = 40 * 100 + 50;
    const auto a = analyse(r, centre, true, {}, bounce);
    ASSERT_EQ(a->error, "");
    EXPECT_EQ(a->crop_w, 64);
    EXPECT_EQ(a->crop_h, 64);
    ASSERT_FALSE(a->pixels.empty());
    for (const std::uint32_t p : a->pixels) {
        const int x = int(p % 100), y = int(p / 100);
        ASSERT_TRUE(x >= a->crop_x && x < a->crop_x + 64 && y >= a->crop_y && y < a->crop_y + 64)
            << p;
    }
    const auto whole = analyse(r, centre, false, {}, bounce);
    EXPECT_LT(a->pixels.size(), whole->pixels.size());
    // The centre's path goes on after the back wall: its bounce ray is followed, the same
    // ray in the crop as in the whole batch.
    ASSERT_TRUE(a->followed);
    EXPECT_EQ(a->ray.org, whole->ray.org);
    EXPECT_EQ(a->hit.prim, whole->hit.prim);
    EXPECT_FALSE(a->detail->follow.empty());
    // A pixel outside the crop has no ray in the batch: not followed, not "no hit".
    const auto outside = analyse(r, 0, true, {}, bounce);
    EXPECT_EQ(outside->error, "");
    EXPECT_FALSE(outside->followed);
    EXPECT_TRUE(outside->detail->follow.empty());
}

// A region dragged on the image (or `set region`) is the pixels whose centres it holds; the
// recording keeps that region's rays, in the batch's order, and follows a pixel inside it.
TEST(AnalyseBatch, ARegionOfTheImageKeepsExactlyItsPixelsRays) {
    // Pixel centres: x + 0.5 in [u0 W, u1 W).
    EXPECT_EQ(region_pixels({0.25f, 0.5f, 0.75f, 1.0f}, 100, 80),
              (std::array<int, 4>{25, 40, 50, 40}));
    EXPECT_EQ(region_pixels({0.0f, 0.0f, 1.0f, 1.0f}, 100, 80),
              (std::array<int, 4>{0, 0, 100, 80}));
    EXPECT_EQ(region_pixels({0.501f, 0.5f, 0.502f, 0.501f}, 100, 80),
              (std::array<int, 4>{50, 40, 1, 1}))
        << "a region holding no centre is the nearest pixel";
    EXPECT_EQ(region_pixels({}, 100, 80), (std::array<int, 4>{18, 8, 64, 64})) << "the centre";
    EXPECT_EQ(region_pixels({}, 40, 30), (std::array<int, 4>{0, 0, 40, 30}));

    const RenderRequest r = request(100, 80);
    const BatchId bounce{Kind::bounce, 1};
    const std::int64_t inside = 50 * 100 + 30;  // (30, 50)
    const auto a = analyse(r, inside, true, parse_region("0.1,0.5,0.4,0.9"), bounce);
    ASSERT_EQ(a->error, "");
    EXPECT_EQ(a->crop_x, 10);
    EXPECT_EQ(a->crop_y, 40);
    EXPECT_EQ(a->crop_w, 30);
    EXPECT_EQ(a->crop_h, 32);
    EXPECT_TRUE(a->cropped());
    EXPECT_EQ(region_name(*a), "30x32 region at (10, 40)");
    const auto whole = analyse(r, inside, false, {}, bounce);
    EXPECT_FALSE(whole->cropped());
    std::vector<std::uint32_t> expected;
    for (const std::uint32_t p : whole->pixels) {
        const int x = int(p % 100), y = int(p / 100);
        if (x >= 10 && x < 40 && y >= 40 && y < 72) expected.push_back(p);
    }
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(a->pixels, expected);
    ASSERT_TRUE(a->followed);
    EXPECT_EQ(a->ray.org, whole->ray.org);
    // The script's words: four fractions in order, or centre.
    for (const char* bad : {"0.5,0.5,0.4,0.9", "0,0,1", "0,0,1,1.5", "a,b,c,d", "0,0,1,1,1"})
        EXPECT_NE(test::error_of([&] { parse_region(bad); }).find("region: '"), std::string::npos)
            << bad;
    EXPECT_TRUE(parse_region("centre").empty());
    EXPECT_EQ(region_text(parse_region("0.1,0.5,0.4,0.9")), "0.1,0.5,0.4,0.9");
    EXPECT_EQ(region_text({}), "centre");
}

TEST(AnalyseBatch, ABatchThePassNeverTracesIsAnErrorNotACrash) {
    const RenderRequest r = request(24, 16);
    EXPECT_NE(analyse(r, -1, false, {}, {Kind::ao, 0})->error.find("only the ao integrator"),
              std::string::npos);
    EXPECT_NE(analyse(r, -1, false, {}, {Kind::bounce, 4})->error.find("max-depth 3"),
              std::string::npos);
    EXPECT_EQ(analyse(r, -1, false, {}, {Kind::bounce, 3})->error, "");
    const RenderRequest primary = request(24, 16, Integrator::primary);
    EXPECT_NE(analyse(primary, -1, false, {}, {Kind::shadow, 0})->error, "");
}

TEST(AnalyseBatch, ARecordingIsStaleForAnotherBatchOrAnotherPass) {
    RenderRequest r = request(24, 16);
    const BatchId bounce{Kind::bounce, 1};
    const auto a = analyse(r, -1, false, {}, bounce);
    EXPECT_FALSE(analysis_stale(*a, r, bounce));
    EXPECT_TRUE(analysis_stale(*a, r, BatchId{}));
    EXPECT_TRUE(analysis_stale(*a, r, {Kind::bounce, 2}));
    const auto camera = analyse(r, -1, false, {}, BatchId{});
    r.settings.max_depth = 5;  // another path: later batches change, camera rays do not
    EXPECT_TRUE(analysis_stale(*a, r, bounce));
    EXPECT_FALSE(analysis_stale(*camera, r, BatchId{}));
}

TEST(AnalyseBatch, PerPixelStatisticsSumTheRaysOfAPixel) {
    std::vector<RayStats> rays(4);
    rays[0] = {1, 2, 3, 60000};
    rays[1] = {10, 20, 7, 60000};
    rays[2] = {100, 200, 1, 1};
    rays[3] = {5, 5, 5, 5};
    const std::vector<std::uint32_t> pixels = {2, 2, 0, 99};  // 99: outside a 2x2 image
    const std::vector<RayStats> p = per_pixel_stats(rays, pixels, 2, 2);
    ASSERT_EQ(p.size(), 4u);
    EXPECT_EQ(p[2].ray_box_tests, 11u);
    EXPECT_EQ(p[2].ray_triangle_tests, 22u);
    EXPECT_EQ(p[2].deepest_level, 7u);
    EXPECT_EQ(p[2].order_misses, 65535u) << "clamped, not wrapped";
    EXPECT_EQ(p[0].ray_box_tests, 100u);
    EXPECT_EQ(p[1].ray_box_tests, 0u);
    EXPECT_EQ(p[3].ray_box_tests, 0u);
}

TEST(AnalyseBatch, TheTabsShowTheChosenBatchAndWriteAnalysisWritesIt) {
    ViewerState s;
    s.scene = cornell();
    s.submitted = request(24, 16);
    EXPECT_EQ(shown_batch(s).detail, nullptr);
    EXPECT_NE(test::error_of([&] { analysis_json(s); }).find("no statistics of batch camera yet"),
              std::string::npos);
    // The camera rays: the frame's own statistics.
    auto frame = std::make_shared<Frame>();
    auto detail = std::make_shared<TraceDetail>();
    detail->rays.resize(24 * 16);
    frame->detail = detail;
    frame->image = Image(24, 16);
    s.frame = frame;
    EXPECT_EQ(shown_batch(s).detail, detail.get());
    EXPECT_EQ(shown_batch(s).pixels.size(), 24u * 16u);
    // Another batch: the analysis once it is of that batch and current.
    apply_setting(s, "batch", "shadow:1");
    EXPECT_EQ(s.batch, (BatchId{Kind::shadow, 1}));
    EXPECT_TRUE(s.analysis_requested);
    EXPECT_EQ(shown_batch(s).detail, nullptr);
    s.analysis = analyse(s.submitted, -1, false, {}, s.batch);
    s.analysis_stale = analysis_stale(*s.analysis, s.submitted, s.batch);
    ASSERT_EQ(s.analysis->error, "");
    const ShownBatch shown = shown_batch(s);
    ASSERT_EQ(shown.detail, s.analysis->detail.get());
    EXPECT_EQ(shown.rays, s.analysis->pixels.size());
    const nlohmann::json json = nlohmann::json::parse(analysis_json(s));
    EXPECT_EQ(json["batch"], "shadow:1");
    EXPECT_EQ(json["rays"], shown.rays);
    EXPECT_EQ(json["crop"], false);
    EXPECT_EQ(json["detail"]["per_ray"]["rays"], shown.rays);
    EXPECT_EQ(json["detail"]["levels"].size(), s.analysis->detail->levels.size());
    EXPECT_FALSE(json["detail"]["levels"].empty());
    // Stale or failed: no figures, and the reason.
    s.analysis_stale = true;
    EXPECT_EQ(shown_batch(s).detail, nullptr);
    apply_setting(s, "batch", "ao");
    s.analysis = analyse(s.submitted, -1, false, {}, s.batch);
    s.analysis_stale = false;
    EXPECT_NE(test::error_of([&] { analysis_json(s); }).find("only the ao integrator"),
              std::string::npos);
    EXPECT_THROW(apply_setting(s, "batch", "bounce:0"), InputError);
    EXPECT_EQ(s.batch, (BatchId{Kind::ao, 0})) << "a refused value leaves the batch";
}

}  // namespace
}  // namespace edacrt::app
