#include "frame_phases.h"

#include "viewer_jobs.h"

namespace edacrt::app {

void sync_worker(ViewerState& s, const std::shared_ptr<const Frame>& frame,
                 std::uint64_t request_id, double dt) {
    if (frame && frame->request == request_id) {
        s.render_error = frame->error;
        s.render_answered = true;
        if (!frame->error.empty() && s.playback.playing) {  // no frame to wait for
            s.playback.playing = false;
            s.playback.error = frame->error;
        }
        if (frame->error.empty() && frame != s.frame) {
            if (frame->preview) s.convergence.clear();
            if (!frame->preview && s.frame && !s.frame->preview &&
                s.frame->request == frame->request && s.frame->spp < frame->spp)
                s.convergence.push_back({frame->seconds, frame->spp,
                                         relative_rms_change(frame->image, s.frame->image)});
            s.frame = frame;
            record_frame_time(s, *frame, s.submitted.method);
        }
    }
    // Playing: the next frame once this one's first full pass is shown.
    advance_playback(s, s.frame && s.frame->request == request_id && !s.frame->preview, dt);
    s.analysis_stale = s.analysis && analysis_stale(*s.analysis, s.submitted, s.batch);
    // A batch other than the camera rays is recorded once the view has its first full pass (not
    // while a drag makes request after request), and again for a new view.
    const bool settled = s.frame && s.frame->request == request_id && !s.frame->preview;
    if (s.batch != BatchId{} && settled && (!s.analysis || s.analysis_stale) && !s.analysis_running)
        s.analysis_requested = true;
}

std::optional<RenderRequest> changed_request(ViewerState& s, int width, int height, bool first) {
    if (width <= 0 || height <= 0) return std::nullopt;
    RenderRequest request = make_request(s, width, height);
    if (!fit_resolution(s, request, s.submitted) || (!first && request == s.submitted))
        return std::nullopt;
    return request;
}

}  // namespace edacrt::app
