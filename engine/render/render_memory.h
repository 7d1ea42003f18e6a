#pragma once
// What a render needs in memory, estimated before it starts from the sizes of the renderer's
// data structures, and the memory it may use, so that a render that cannot fit is refused
// up front with the figure instead of failing after minutes.
#include <cstdint>
#include <string>

#include "render/render_settings.h"

namespace edacrt {

/// Bytes per ray of a traced batch: the ray, its hit and the tracer's own per-ray state (of the
/// method that keeps the most); with `detail`, also the per-ray statistics of a TraceDetail.
std::uint64_t trace_bytes_per_ray(bool detail = false);

/// Bytes of wavefront state per path (for ao per camera ray, with its ao_samples rays),
/// counted from the integrators' arrays.
std::uint64_t wavefront_bytes_per_path(const RenderSettings& settings);

/// Peak bytes of a Renderer with `settings`: the film and the pass's samples for every pixel,
/// the state of one wavefront, and `extra_bytes_per_pixel` the caller keeps per pixel
/// (its copies of the image, output buffers).
std::uint64_t render_memory_bytes(const RenderSettings& settings,
                                  std::uint64_t extra_bytes_per_pixel = 0);

/// The memory a process may use: physical memory, or less when a cgroup limit, the
/// address-space limit (ulimit -v) or $EDACRT_MEMORY_LIMIT (bytes) says so.
struct MemoryLimit {
    std::uint64_t bytes;
    std::string source;  // "physical memory", ...
};
MemoryLimit memory_limit();

/// Throws InputError with the figures when render_memory_bytes() exceeds memory_limit().
void check_render_memory(const RenderSettings& settings, std::uint64_t extra_bytes_per_pixel = 0);

}  // namespace edacrt
