#include "render_worker.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>

#include "render/renderer.h"
#include "render/sampler.h"

namespace edacrt::app {
namespace {

bool same_method(const RenderRequest& a, const RenderRequest& b) {
    return a.method == b.method && a.embree_mode == b.embree_mode && a.params == b.params;
}

}  // namespace

RenderWorker::RenderWorker() : thread_([this] { run(); }) {}

RenderWorker::~RenderWorker() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
        cancel_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

std::uint64_t RenderWorker::submit(RenderRequest request) {
    std::uint64_t id;
    {
        std::lock_guard lock(mutex_);
        pending_ = std::make_shared<const RenderRequest>(std::move(request));
        id = ++submitted_;
        idle_ = false;
        cancel_ = true;  // under the lock, so it cannot cancel the request it announces
    }
    wake_.notify_all();
    return id;
}

std::shared_ptr<const Frame> RenderWorker::latest() const {
    std::lock_guard lock(mutex_);
    return latest_;
}

void RenderWorker::publish(std::shared_ptr<const Frame> frame) {
    std::lock_guard lock(mutex_);
    latest_ = std::move(frame);
}

void RenderWorker::set_paused(bool paused) {
    {
        std::lock_guard lock(mutex_);
        if (paused_ && !paused) idle_ = false;  // the worker looks again before it is idle
        paused_ = paused;
    }
    wake_.notify_all();
}

bool RenderWorker::wait_idle(std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    return idle_changed_.wait_for(lock, timeout, [&] { return idle_; });
}

void RenderWorker::run() {
    std::shared_ptr<const RenderRequest> current, traced;  // traced: what `tracer` was made for
    std::shared_ptr<const Scene> geometry;                 // what `tracer` and `renderer` hold now
    std::uint64_t id = 0;
    std::unique_ptr<Tracer> tracer;
    std::unique_ptr<Renderer> renderer;
    std::unique_ptr<tbb::task_arena> arena;
    std::shared_ptr<const TraceDetail> detail;
    double seconds = 0.0, first_pass_seconds = 0.0;
    UpdateStats pending_update;  // how the tracer took the current request's scene
    bool fresh = false;          // a request not yet started
    for (;;) {
        {
            std::unique_lock lock(mutex_);
            const auto has_work = [&] {
                return quit_ || pending_ ||
                       (current && !paused_ &&
                        (fresh || (renderer && renderer->film().passes() < current->spp_target)));
            };
            while (!has_work()) {
                if (!idle_) {  // again after a wake-up that brought no work (resume at target)
                    idle_ = true;
                    idle_changed_.notify_all();
                }
                wake_.wait(lock);
            }
            idle_ = false;
            if (quit_) return;
            if (pending_) {
                current = std::move(pending_);
                pending_.reset();
                id = submitted_;
                cancel_ = false;
                fresh = true;
            }
        }
        const RenderRequest& request = *current;
        try {
            if (fresh) {
                fresh = false;
                renderer.reset();
                detail.reset();
                seconds = 0.0;
                const int all = tbb::task_arena::automatic;  // a copy: no ODR use of the member
                arena =
                    std::make_unique<tbb::task_arena>(request.threads > 0 ? request.threads : all);
                // The tracer takes the request's scene: from scratch for another method or
                // scene, as the request says for another frame of the same animation.
                UpdateStats update;
                if (!tracer || !traced || !same_method(*traced, request) ||
                    (geometry != request.scene &&
                     !(request.animation && request.animation == traced->animation))) {
                    tracer.reset();
                    geometry.reset();
                    tracer = make_tracer(request.method, request.params, request.embree_mode);
                    // An animation's first frame is built as its later ones are taken (a
                    // tree Embree can refit), which reports `rebuilt`.
                    const SceneUpdate how =
                        request.animation ? request.update : SceneUpdate::rebuild;
                    arena->execute([&] { update = tracer->update_scene(*request.scene, how); });
                } else if (geometry != request.scene) {
                    arena->execute(
                        [&] { update = tracer->update_scene(*request.scene, request.update); });
                }
                traced = current;
                geometry = request.scene;
                if (request.preview_scale > 1) {
                    RenderSettings small = request.settings;
                    small.width = std::max(1, small.width / request.preview_scale);
                    small.height = std::max(1, small.height / request.preview_scale);
                    Renderer preview(*request.scene, *tracer, request.camera, small);
                    bool done = false;
                    arena->execute([&] { done = preview.render_pass(&cancel_); });
                    if (!done) continue;
                    auto frame = std::make_shared<Frame>();
                    frame->request = id;
                    frame->preview = true;
                    frame->time = request.time;
                    frame->image = preview.film().mean();
                    frame->spp = 1;
                    publish(std::move(frame));
                }
                renderer = std::make_unique<Renderer>(*request.scene, *tracer, request.camera,
                                                      request.settings);
                pending_update = update;
            }
            const int passes = renderer->film().passes();
            if (request.animation && request.shutter > 0.0) {
                // Motion blur: this pass (of one sample) at its own time of the shutter,
                // added to the film.
                auto scene = request.animation->at(
                    shutter_time(request.time, request.shutter, std::uint32_t(passes)));
                if (scene != geometry) {
                    arena->execute([&] { tracer->update_scene(*scene, request.update); });
                    renderer->scene_changed(*scene, true);
                    geometry = std::move(scene);
                }
            }
            auto captured =
                renderer->film().passes() == 0 ? std::make_shared<TraceDetail>() : nullptr;
            bool done = false;
            // With a shutter, one sample per pass: each pass is its own time.
            const int samples =
                passes == 0 || (request.animation && request.shutter > 0.0)
                    ? 1
                    : std::clamp(request.spp_target - passes, 1, request.settings.samples_per_pass);
            arena->execute(
                [&] { done = renderer->render_pass(&cancel_, captured.get(), samples); });
            if (!done) continue;                       // cancelled: a new request is waiting
            seconds += renderer->last_pass().seconds;  // without the statistics' recording
            if (captured) {
                detail = std::move(captured);
                first_pass_seconds = seconds;
            }
            auto frame = std::make_shared<Frame>();
            frame->request = id;
            frame->image = renderer->film().mean();
            frame->spp = renderer->film().passes();
            frame->seconds = seconds;
            frame->total = renderer->total();
            frame->detail = detail;
            frame->time = request.time;
            frame->update = pending_update;
            frame->first_pass_seconds = first_pass_seconds;
            publish(std::move(frame));
        } catch (const std::exception& e) {
            auto frame = std::make_shared<Frame>();
            frame->request = id;
            frame->error = e.what();
            publish(std::move(frame));
            current.reset();
            renderer.reset();
            tracer.reset();
            traced.reset();
            geometry.reset();
        }
    }
}

}  // namespace edacrt::app
