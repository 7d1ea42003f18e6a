#pragma once
// Per-ray statistics of the tracers that trace one ray at a time (naive, bvh), hooked in as the
// recursion's are (edacrt_observer.h): the tracer is a template on its observer, and
// NullRayObserver's empty hook compiles the recording out of the fast path. The totals
// (TraceStats) are counted either way.
#include <cstddef>
#include <cstdint>

#include "trace/trace_stats.h"

namespace edacrt {

struct NullRayObserver {
    void traced(std::size_t, std::uint32_t, std::uint32_t) const {}
};

/// Fills TraceDetail::rays; each ray's entry is written once, by the thread that traced it.
class RayStatsObserver {
  public:
    explicit RayStatsObserver(TraceDetail& detail) : rays_(detail.rays.data()) {}

    void traced(std::size_t ray, std::uint32_t box_tests, std::uint32_t triangle_tests) const {
        rays_[ray].ray_box_tests = box_tests;
        rays_[ray].ray_triangle_tests = triangle_tests;
    }

  private:
    RayStats* rays_;
};

/// trace(observer) with the observer `detail` asks for: RayStatsObserver with it, the null one
/// without.
template <class Trace>
TraceStats with_ray_observer(TraceDetail* detail, const Trace& trace) {
    if (!detail) return trace(NullRayObserver{});
    return trace(RayStatsObserver(*detail));
}

}  // namespace edacrt
