#pragma once
// The frames of an animation for the viewer: snapshots of the scene at given times that the
// render, the recording and the comparisons share across threads. Each snapshot is written
// (Animation::frame()) into a recycled buffer that returns to the pool when its last holder
// lets go, so playing reallocates nothing once there are enough buffers (about four: the
// frame shown, the request in flight, the next one, a recording).
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "scene/animation.h"

namespace edacrt::app {

class FramePool {
  public:
    /// Takes the animated scene (its animation must not be null).
    explicit FramePool(AnimatedScene animated);
    ~FramePool();
    FramePool(const FramePool&) = delete;
    FramePool& operator=(const FramePool&) = delete;

    /// The scene at time `t` seconds: the same snapshot again while the last one asked for
    /// that time is still held, else a recycled buffer rewritten. Thread-safe. Throws
    /// InputError (Animation::frame(): a non-finite t, a bad key frame, non-finite geometry).
    std::shared_ptr<const Scene> at(double t);

    /// One period of a deformation, or the time of the last key frame (Animation::duration()).
    double duration() const { return duration_; }
    const std::string& spec() const { return spec_; }
    std::size_t triangle_count() const { return triangles_; }

    /// Buffers allocated so far (held or free).
    std::size_t buffers() const;

  private:
    struct Free;  // the free buffers, shared with the snapshots' deleters
    std::shared_ptr<Free> free_;
    mutable std::mutex mutex_;  // guards animation_ (frame() may read files), last_, allocated_
    AnimatedScene animated_;    // the geometry of time 0, copied into each new buffer
    std::weak_ptr<const Scene> last_;
    double last_time_ = 0.0;
    std::size_t allocated_ = 0;
    double duration_;
    std::string spec_;
    std::size_t triangles_;
};

}  // namespace edacrt::app
