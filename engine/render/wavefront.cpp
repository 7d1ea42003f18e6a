#include "render/wavefront.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>

namespace edacrt {

void Wavefront::camera_rays(std::size_t begin, std::size_t end, std::vector<Ray>& rays) const {
    rays.resize(end - begin);
    const auto width = std::size_t(settings.width);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 1024), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const glm::vec2 jitter = sampler(std::uint32_t(i)).get_2d(0);
            rays[i - begin] =
                projection.ray(float(i % width) + jitter.x, float(i / width) + jitter.y);
        }
    });
}

bool Wavefront::trace(std::span<const Ray> rays, std::span<Hit> hits, Query query) {
    if (cancelled()) return false;
    const auto start = std::chrono::steady_clock::now();
    stats.trace += tracer.trace(rays, hits, query);
    stats.trace_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++stats.batches;
    return true;
}

}  // namespace edacrt
