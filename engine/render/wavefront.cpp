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

bool Wavefront::trace_camera(std::span<const Ray> rays, std::span<Hit> hits) {
    if (!trace(rays, hits, Query::closest)) return false;
    if (primary_detail) {
        TraceDetail tile;
        std::vector<Hit> again(rays.size());
        tracer.trace(rays, again, Query::closest, &tile);
        primary_detail->rays.insert(primary_detail->rays.end(), tile.rays.begin(), tile.rays.end());
        if (primary_detail->levels.size() < tile.levels.size())
            primary_detail->levels.resize(tile.levels.size());
        for (std::size_t level = 0; level < tile.levels.size(); ++level)
            primary_detail->levels[level] += tile.levels[level];
    }
    return true;
}

}  // namespace edacrt
