#pragma once
// The viewer's render thread. The UI submits a RenderRequest (a full copy of everything that
// defines the image); the worker cancels the pass in flight (the renderer checks before every
// batch), renders a low-resolution preview pass, then accumulates full-resolution passes and
// publishes each as a Frame. The UI never waits for the renderer: submit() and latest() only
// take a mutex held for a pointer swap.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

#include "frame_pool.h"
#include "render/image.h"
#include "render/render_settings.h"
#include "render/wavefront.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace edacrt::app {

struct RenderRequest {
    std::shared_ptr<const Scene> scene;
    Camera camera;
    Method method = Method::edacrt;
    EdacrtParams params;
    EmbreeMode embree_mode = kDefaultEmbreeMode;
    RenderSettings settings;  // width and height: the full resolution
    int spp_target = 1024;
    int threads = 0;        // 0: all
    int preview_scale = 4;  // the first pass at 1/preview_scale of the resolution (1: none)
    // An animation: `scene` is its frame at `time` seconds (FramePool::at), and the tracer
    // takes each new frame as `update` says. With `shutter` > 0 the passes are rendered at
    // times spread over [time - shutter/2, time + shutter/2] (the first at `time`) and
    // average into motion blur.
    std::shared_ptr<FramePool> animation;
    double time = 0.0;
    double shutter = 0.0;
    SceneUpdate update = SceneUpdate::refit;

    bool operator==(const RenderRequest&) const = default;
};

/// One published pass: the film's mean so far and what the pass cost.
struct Frame {
    std::uint64_t request = 0;  // the submit() it belongs to
    bool preview = false;
    Image image;  // linear radiance
    int spp = 0;
    double seconds = 0.0;  // rendering time of the request so far
    PassStats total;       // summed over the request's full-resolution passes
    // Statistics of the first full-resolution pass's camera rays (per level and per pixel).
    std::shared_ptr<const TraceDetail> detail;
    std::string error;  // why the request could not be rendered (bad parameters)
    // The request's animation time, and how the tracer took its scene before the first pass
    // (set_scene: rebuilt; a frame of the animation: as RenderRequest::update says; the scene
    // it already had: none, 0 s).
    double time = 0.0;
    UpdateStats update;
    double first_pass_seconds = 0.0;  // the first full-resolution pass (1 spp)
};

class RenderWorker {
  public:
    RenderWorker();
    ~RenderWorker();
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    /// Replaces the current request; returns its number. Never blocks on rendering.
    std::uint64_t submit(RenderRequest request);

    /// Stops accumulating after the pass in flight, or resumes; the film is kept.
    void set_paused(bool paused);

    /// The newest published frame (null before the first).
    std::shared_ptr<const Frame> latest() const;

    /// Blocks until the worker has nothing to do (target reached, paused, or an error) and
    /// waits for a change; false when `timeout` passed first. No frame is published while it
    /// stays idle.
    bool wait_idle(std::chrono::milliseconds timeout) const;

  private:
    void run();
    void publish(std::shared_ptr<const Frame> frame);

    mutable std::mutex mutex_;
    std::condition_variable wake_;
    mutable std::condition_variable idle_changed_;
    std::shared_ptr<const RenderRequest> pending_;  // guarded by mutex_
    std::uint64_t submitted_ = 0;                   // guarded by mutex_
    bool quit_ = false;                             // guarded by mutex_
    bool paused_ = false;                           // guarded by mutex_
    bool idle_ = false;                             // guarded by mutex_
    std::shared_ptr<const Frame> latest_;           // guarded by mutex_
    std::atomic<bool> cancel_{false};
    std::thread thread_;
};

}  // namespace edacrt::app
