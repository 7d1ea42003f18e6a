#include "render/wavefront.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>

namespace edacrt {
namespace {

/// The camera ray of a path: through its pixel, jittered by the sample's pair 0.
Ray camera_ray(const PinholeProjection& projection, std::size_t width, std::size_t pixel,
               const PixelSampler& sampler) {
    const glm::vec2 jitter = sampler.get_2d(0);
    return projection.ray(float(pixel % width) + jitter.x, float(pixel / width) + jitter.y);
}

}  // namespace

void Wavefront::camera_rays(std::size_t begin, std::size_t end, std::vector<Ray>& rays) const {
    rays.resize(end - begin);
    const auto width = std::size_t(settings.width);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 1024), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
            rays[i - begin] = camera_ray(projection, width, i % pixels, sampler(i));
    });
}

std::vector<Ray> first_pass_camera_rays(const Camera& camera, const RenderSettings& settings) {
    const PinholeProjection projection(camera, settings.width, settings.height);
    const auto width = std::size_t(settings.width);
    std::vector<Ray> rays(width * std::size_t(settings.height));
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i)
                rays[i] = camera_ray(projection, width, i,
                                     PixelSampler(settings.seed, std::uint32_t(i), 0));
        });
    return rays;
}

void Wavefront::trace_timed(BatchId id, std::span<const Ray> rays, std::span<Hit> hits) {
    const auto start = std::chrono::steady_clock::now();
    stats.trace += tracer.trace(rays, hits, batch_query(id));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.trace_seconds += seconds;
    ++stats.batches;
    stats.add_batch({id, 1, rays.size(), seconds});
}

}  // namespace edacrt
