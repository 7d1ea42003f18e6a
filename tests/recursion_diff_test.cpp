// Two recursions of the same rays (the Recursion tab's "against"): the node pairs where their
// decisions first differ, on hand-made recordings and on EDACRT against its presets.
#include "recursion_diff.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "input_error.h"
#include "render/batch_capture.h"
#include "scene/builtin_scenes.h"
#include "script_runner.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

/// A split node at `depth` over `rays` rays and `tris` triangles, its plane at x = plane.
NodeRecord split(std::uint16_t depth, std::uint32_t rays, std::uint32_t tris, float plane) {
    NodeRecord n;
    n.depth = depth;
    n.rays = rays;
    n.triangles = tris;
    n.box = {glm::vec3(0.0f), glm::vec3(1.0f)};
    n.leaf = false;
    n.axis = 0;
    n.chosen = 0;
    n.candidates.resize(1);
    n.candidates[0].plane = plane;
    return n;
}

NodeRecord leaf(std::uint16_t depth, std::uint32_t rays, std::uint32_t tris) {
    NodeRecord n = split(depth, rays, tris, 0.0f);
    n.leaf = true;
    n.candidates.clear();
    n.chosen = -1;
    return n;
}

/// Root 0 (left 1, right 2); node 2 splits into leaves 3 and 4.
TraceDetail tree() {
    TraceDetail d;
    d.nodes = {split(0, 100, 40, 0.5f), leaf(1, 60, 20), split(1, 70, 20, 0.7f), leaf(2, 30, 10),
               leaf(2, 50, 10)};
    d.nodes[0].children[0] = 1;
    d.nodes[0].children[1] = 2;
    d.nodes[2].children[0] = 3;
    d.nodes[2].children[1] = 4;
    for (int i : {1, 2}) d.nodes[std::size_t(i)].parent = 0;
    for (int i : {3, 4}) d.nodes[std::size_t(i)].parent = 2;
    return d;
}

TEST(RecursionDiff, EachBranchReportsItsFirstDifferenceOnly) {
    const TraceDetail a = tree();
    EXPECT_TRUE(first_differences(a, a).empty());
    EXPECT_TRUE(first_differences(a, TraceDetail{}).empty()) << "nothing recorded in B";

    TraceDetail b = tree();
    b.nodes[0].left_first = false;  // the root's order
    auto d = first_differences(a, b);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].node_a, 0);
    EXPECT_EQ(d[0].what, "left child first against right first");

    b = tree();
    b.nodes[1] = split(1, 60, 20, 0.2f);  // a leaf in A, a split in B
    b.nodes[2].filter_skipped[1] = true;  // and below the root's other child, a filter
    b.nodes[4].leaf = false;              // under it: not compared
    d = first_differences(a, b);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0].node_a, 1);
    EXPECT_EQ(d[0].what, "a leaf against a split");
    EXPECT_EQ(d[1].node_a, 2);
    EXPECT_EQ(d[1].depth, 1);
    EXPECT_EQ(d[1].what, "the right child's filter run against skipped");

    b = tree();
    b.nodes[2].candidates[0].plane = 0.75f;
    d = first_differences(a, b);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].what, "split plane x = 0.7 against x = 0.75");

    b = tree();
    b.nodes[3].rays = 31;  // the same decisions above, another input here
    d = first_differences(a, b);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].node_a, 3);
    EXPECT_EQ(d[0].what, "input: 30 rays x 10 triangles against 31 x 10");
    EXPECT_EQ(first_differences(a, b, 0).size(), 0u) << "the limit";
}

/// The Cornell box path-traced by EDACRT at width x height, three bounces.
RenderRequest cornell(int width, int height) {
    RenderRequest r;
    r.scene = std::make_shared<const Scene>(make_builtin_scene("builtin:cornell"));
    r.camera = *r.scene->camera;
    r.settings.width = width;
    r.settings.height = height;
    r.settings.integrator = Integrator::path;
    r.settings.max_depth = 3;
    r.method = Method::edacrt;
    return r;
}

TEST(RecursionDiff, TheRecordingAgainstItsOwnPresetAgreesAndAgainstDacrtDiffers) {
    const RenderRequest r = cornell(64, 48);
    for (const BatchId batch : {BatchId{}, parse_batch("bounce:1")}) {
        SCOPED_TRACE(batch_name(batch));
        const auto same = analyse(r, -1, false, {}, batch, "default");
        ASSERT_EQ(same->error, "");
        ASSERT_TRUE(same->against_detail);
        EXPECT_EQ(same->against, "default");
        EXPECT_TRUE(same->differences.empty()) << same->differences.front().what;
        ASSERT_EQ(same->against_detail->levels.size(), same->detail->levels.size());
        for (std::size_t i = 0; i < same->detail->levels.size(); ++i)
            EXPECT_EQ(same->against_detail->levels[i].ray_box_tests,
                      same->detail->levels[i].ray_box_tests);

        const auto dacrt = analyse(r, -1, false, {}, batch, "dacrt");
        ASSERT_EQ(dacrt->error, "");
        ASSERT_TRUE(dacrt->against_detail);
        EXPECT_EQ(dacrt->against_detail->rays.size(), dacrt->detail->rays.size());
        // Sampled alpha against area ratios: the recursions part somewhere.
        ASSERT_FALSE(dacrt->differences.empty());
        for (const DecisionDifference& d : dacrt->differences) {
            EXPECT_FALSE(d.what.empty());
            EXPECT_EQ(dacrt->detail->nodes[std::size_t(d.node_a)].depth, d.depth);
        }
        EXPECT_FALSE(analyse(r, -1, false, {}, batch)->against_detail) << "none asked for";
    }
}

// The heat map of a recording against another recursion: A's, B's or B - A per pixel, signed,
// and A's again when the recording is stale or nothing was compared.
TEST(RecursionDiff, TheHeatMapShowsAOrBOrTheirDifference) {
    const RenderRequest r = cornell(40, 30);
    ViewerState s;
    s.analysis = analyse(r, -1, false, {}, parse_batch("bounce:1"), "dacrt");
    s.batch = parse_batch("bounce:1");
    ASSERT_EQ(s.analysis->error, "");
    s.view = View::box_tests;
    EXPECT_FALSE(heat_image(s).difference());
    const std::vector<float> a = heat_image(s).values(s.view);
    s.heat_of = HeatOf::b;
    const std::vector<float> b = heat_image(s).values(s.view);
    s.heat_of = HeatOf::difference;
    EXPECT_TRUE(heat_image(s).difference());
    const std::vector<float> d = heat_image(s).values(s.view);
    ASSERT_EQ(a.size(), 40u * 30u);
    ASSERT_EQ(b.size(), a.size());
    ASSERT_EQ(d.size(), a.size());
    bool differs = false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i], float(s.analysis->pixel_stats[i].ray_box_tests));
        EXPECT_EQ(b[i], float(s.analysis->against_pixel_stats[i].ray_box_tests));
        EXPECT_EQ(d[i], b[i] - a[i]);
        differs |= d[i] != 0.0f;
    }
    EXPECT_TRUE(differs) << "EDACRT and DACRT make other box tests somewhere";
    // write-analysis: B's statistics and the differences beside A's.
    const nlohmann::json json = nlohmann::json::parse(analysis_json(s));
    ASSERT_TRUE(json.contains("against"));
    EXPECT_EQ(json["against"]["preset"], "dacrt");
    EXPECT_EQ(json["against"]["rays"], json["rays"]);
    EXPECT_EQ(json["against"]["differences"].size(), s.analysis->differences.size());
    EXPECT_NE(json["against"]["detail"]["per_ray"], json["detail"]["per_ray"]);
    s.analysis_stale = true;
    EXPECT_NE(test::error_of([&] { analysis_json(s); }).find("no statistics of batch bounce:1"),
              std::string::npos)
        << "a stale recording is not written";
    EXPECT_FALSE(heat_image(s).difference()) << "a stale recording: A's, from the batch";
    s.view = View::render;
    EXPECT_TRUE(heat_image(s).pixels.empty());
}

}  // namespace
}  // namespace edacrt::app
