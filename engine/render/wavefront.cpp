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
            const glm::vec2 jitter = sampler(i).get_2d(0);
            const std::size_t pixel = i % pixels;
            rays[i - begin] =
                projection.ray(float(pixel % width) + jitter.x, float(pixel / width) + jitter.y);
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
