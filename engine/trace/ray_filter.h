#pragma once
// The filter of divide-and-conquer ray tracing: partitions a node's rays by a child box.
#include <cstddef>

#include "geometry/aabb.h"
#include "trace/ray_stream.h"

namespace edacrt {

/// Ranges of at least two blocks are filtered in parallel, in fixed blocks of this many rays
/// (so the result is the same for any thread count): about 10 us of work each.
inline constexpr std::size_t kParallelFilterRays = 4096;

/// Moves the rays of [begin, begin + count) that reach `box` before their t_far (intersect_box)
/// to the front of the range and returns how many there are. Not stable, but deterministic.
std::size_t filter_rays(const RayStream& stream, std::size_t begin, std::size_t count,
                        const Aabb& box);

}  // namespace edacrt
