#include <algorithm>
#include <cmath>

#include "viewer_state.h"

namespace edacrt::app {

void seek(ViewerState& s, double t) {
    Playback& p = s.playback;
    if (!p.frames || !std::isfinite(t)) return;
    const double duration = p.frames->duration();
    if (duration <= 0.0) {  // a still animation: nothing to play
        t = 0.0;
        p.playing = false;
    } else if (p.loop) {
        if (t < 0.0 || t > duration) t -= std::floor(t / duration) * duration;  // the end stays
    } else if (t >= duration) {
        t = duration;
        p.playing = false;
    } else {
        t = std::max(t, 0.0);
    }
    try {
        s.scene = p.frames->at(t);
        p.time = t;
        p.error.clear();
    } catch (const std::exception& e) {
        p.error = e.what();
        p.playing = false;
    }
}

void advance_playback(ViewerState& s, bool frame_done, double dt) {
    Playback& p = s.playback;
    if (!p.frames || !p.playing) {
        p.waited = 0.0;
        return;
    }
    // The render is held (paused, or methods being compared): the animation waits too.
    if (s.ui.paused || s.comparing) return;
    p.waited += dt;
    if (!frame_done) return;
    seek(s, p.time + p.waited * double(p.speed));
    p.waited = 0.0;
}

void toggle_play(ViewerState& s) {
    Playback& p = s.playback;
    if (!p.frames) return;
    p.playing = !p.playing;
    p.waited = 0.0;
    if (p.playing && !p.loop && p.time >= p.frames->duration()) seek(s, 0.0);
}

void record_frame_time(ViewerState& s, const Frame& frame, Method method) {
    Playback& p = s.playback;
    if (!p.frames || frame.preview || frame.spp != 1) return;
    // Another view of the frame just recorded (a camera move) is not another frame.
    if (!p.history.empty() && p.history.back().time == frame.time &&
        p.history.back().method == method)
        return;
    p.history.push_back({frame.time, method, frame.image.width, frame.image.height,
                         frame.update.work, frame.update.seconds, frame.first_pass_seconds});
    if (p.history.size() > Playback::kHistory)
        p.history.erase(p.history.begin(),
                        p.history.begin() + std::ptrdiff_t(p.history.size() - Playback::kHistory));
}

}  // namespace edacrt::app
