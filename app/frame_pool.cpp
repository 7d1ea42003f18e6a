#include "frame_pool.h"

#include <stdexcept>
#include <utility>

namespace edacrt::app {

struct FramePool::Free {
    std::mutex mutex;
    std::vector<std::unique_ptr<Scene>> buffers;
};

FramePool::FramePool(AnimatedScene animated)
    : free_(std::make_shared<Free>()), animated_(std::move(animated)) {
    if (!animated_.animation) throw std::invalid_argument("FramePool: a still scene");
    duration_ = animated_.animation->duration();
    spec_ = animated_.animation->spec();
    triangles_ = animated_.scene.triangle_count();
}

FramePool::~FramePool() = default;

std::shared_ptr<const Scene> FramePool::at(double t) {
    std::lock_guard lock(mutex_);
    if (auto last = last_.lock(); last && last_time_ == t) return last;
    std::unique_ptr<Scene> buffer;
    {
        std::lock_guard free_lock(free_->mutex);
        if (!free_->buffers.empty()) {
            buffer = std::move(free_->buffers.back());
            free_->buffers.pop_back();
        }
    }
    if (!buffer) {
        buffer = std::make_unique<Scene>(animated_.scene);
        ++allocated_;
    }
    const auto give_back = [free = std::weak_ptr<Free>(free_)](Scene* scene) {
        std::unique_ptr<Scene> owned(scene);
        if (const auto pool = free.lock()) {
            std::lock_guard free_lock(pool->mutex);
            pool->buffers.push_back(std::move(owned));
        }
    };
    // A buffer that fails to animate goes back to the pool (the next frame() rewrites it).
    std::shared_ptr<Scene> snapshot(buffer.release(), give_back);
    animated_.animation->frame(t, *snapshot);
    last_ = snapshot;
    last_time_ = t;
    return snapshot;
}

std::size_t FramePool::buffers() const {
    std::lock_guard lock(mutex_);
    return allocated_;
}

}  // namespace edacrt::app
