// The viewer's window-free phases (app/frame_phases.h): worker sync takes only the request in
// force's frames, and submit asks for a render only when what is shown is no longer what is asked
// for.
#include <gtest/gtest.h>

#include <memory>

#include "frame_phases.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

std::shared_ptr<const Frame> frame(std::uint64_t request, int spp, bool preview = false,
                                   std::string error = "") {
    auto f = std::make_shared<Frame>();
    f->request = request;
    f->spp = spp;
    f->preview = preview;
    f->error = std::move(error);
    f->image = Image(4, 2);
    for (glm::vec3& p : f->image.pixels) p = glm::vec3(float(spp));
    return f;
}

TEST(ViewerPhases, WorkerSyncTakesOnlyTheRequestInForce) {
    ViewerState s;
    sync_worker(s, frame(1, 1), 2, 0.0);
    EXPECT_FALSE(s.frame) << "a frame of an older request";
    EXPECT_FALSE(s.render_answered);
    sync_worker(s, frame(2, 0, true), 2, 0.0);
    ASSERT_TRUE(s.frame);
    EXPECT_TRUE(s.frame->preview);
    EXPECT_TRUE(s.render_answered);
    sync_worker(s, frame(2, 1), 2, 0.0);
    sync_worker(s, frame(2, 4), 2, 0.0);
    ASSERT_EQ(s.convergence.size(), 1u) << "one point per pass after the first";
    EXPECT_EQ(s.convergence[0].spp, 4);
    EXPECT_DOUBLE_EQ(s.convergence[0].change, 3.0);  // |4 - 1| / 1
    const auto shown = s.frame;
    sync_worker(s, nullptr, 2, 0.0);
    EXPECT_EQ(s.frame, shown) << "nothing new: the pass stays";
    sync_worker(s, frame(2, 0, true), 2, 0.0);
    EXPECT_TRUE(s.convergence.empty()) << "a preview starts a new render";
    sync_worker(s, frame(2, 0, false, "c-i (C_I) must be positive"), 2, 0.0);
    EXPECT_EQ(s.render_error, "c-i (C_I) must be positive");
    EXPECT_TRUE(s.frame->preview) << "an error shows no image of its own";
}

TEST(ViewerPhases, AFailedRenderStopsPlayback) {
    ViewerState s;
    load_into(s, "builtin:cornell", {}, "wave");
    ASSERT_TRUE(s.playback.frames) << s.scene_error;
    s.playback.playing = true;
    sync_worker(s, frame(1, 0, false, "out of memory"), 1, 0.1);
    EXPECT_FALSE(s.playback.playing);
    EXPECT_EQ(s.playback.error, "out of memory");
}

TEST(ViewerPhases, SubmitAsksOnlyForWhatChanged) {
    ViewerState s;
    load_into(s, "builtin:cornell");
    ASSERT_TRUE(s.scene) << s.scene_error;
    EXPECT_FALSE(changed_request(s, 0, 0, true)) << "no image region yet";
    auto first = changed_request(s, 64, 48, true);
    ASSERT_TRUE(first);
    EXPECT_EQ(first->settings.width, 64);
    s.submitted = *first;
    EXPECT_FALSE(changed_request(s, 64, 48, false)) << "the render asked for is in progress";
    apply_setting(s, "max-depth", "3");
    const auto deeper = changed_request(s, 64, 48, false);
    ASSERT_TRUE(deeper);
    EXPECT_EQ(deeper->settings.max_depth, 3);
    s.submitted = *deeper;
    const auto wider = changed_request(s, 80, 48, false);
    ASSERT_TRUE(wider) << "a new image region";
    EXPECT_EQ(wider->settings.width, 80);
}

}  // namespace
}  // namespace edacrt::app
