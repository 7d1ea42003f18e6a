// Ambient occlusion: the fraction of a cosine-weighted hemisphere around the geometric normal
// that is open within ao_distance, times the diffuse albedo (Kd and its texture): the radiance
// of a Lambertian surface under a white sky of radiance 1 that nothing else reflects. One batch
// of camera rays, then one any-hit batch of ao_samples rays per hit.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/common.hpp>

#include "render/wavefront.h"

namespace edacrt {

bool render_ao(Wavefront& wf, std::size_t begin, std::size_t end, std::span<glm::vec3> radiance) {
    WavefrontBuffers& b = wf.buffers;
    std::vector<Ray>& rays = b.rays;
    wf.camera_rays(begin, end, rays);
    std::vector<Hit>& hits = b.hits;
    hits.assign(rays.size(), Hit{});
    if (!wf.trace({}, rays, hits, [&](std::size_t i) { return begin + i; })) return false;

    // Compact the hits; their AO rays are consecutive, ao_samples per hit.
    std::vector<std::uint32_t>& hit_pixels = b.indices;
    hit_pixels.clear();
    for (std::size_t i = 0; i < hits.size(); ++i)
        if (hits[i].hit()) hit_pixels.push_back(std::uint32_t(i));
    const auto n = std::size_t(wf.settings.ao_samples);
    const float distance =
        wf.settings.ao_distance > 0.0f ? wf.settings.ao_distance : 0.25f * wf.shading.diagonal;
    std::vector<Ray>& ao_rays = b.secondary;
    ao_rays.resize(hit_pixels.size() * n);
    std::vector<glm::vec3>& albedo = b.albedo;
    albedo.resize(hit_pixels.size());
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, hit_pixels.size(), 256), [&](const auto& range) {
            for (std::size_t h = range.begin(); h != range.end(); ++h) {
                const std::size_t i = hit_pixels[h];
                const Surface s = make_surface(wf.scene, rays[i], hits[i]);
                albedo[h] = glm::clamp(wf.scene.materials[s.material].kd, 0.0f, 1.0f) * s.texture;
                const PixelSampler sampler = wf.sampler(begin + i);
                for (std::size_t k = 0; k < n; ++k) {
                    const glm::vec2 u = sampler.get_2d(1, std::uint32_t(k), std::uint32_t(n));
                    ao_rays[h * n + k] = spawn_ray(s, sample_cosine_hemisphere(s.ng, u), distance);
                }
            }
        });
    std::vector<Hit>& ao_hits = b.secondary_hits;
    ao_hits.assign(ao_rays.size(), Hit{});
    if (!wf.trace({BatchId::Kind::ao, 0}, ao_rays, ao_hits,
                  [&](std::size_t j) { return begin + hit_pixels[j / n]; }))
        return false;

    std::fill(radiance.begin(), radiance.end(), glm::vec3(0.0f));
    for (std::size_t h = 0; h < hit_pixels.size(); ++h) {
        std::size_t open = 0;
        for (std::size_t k = 0; k < n; ++k) open += !ao_hits[h * n + k].hit();
        radiance[hit_pixels[h]] = albedo[h] * (float(open) / float(n));
    }
    return true;
}

}  // namespace edacrt
