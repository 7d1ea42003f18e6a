#include "render/eye_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <string>

#include "util/error.h"
#include "util/hash_random.h"

namespace edacrt {
namespace {

void validate(const EyeLightSettings& s) {
    if (s.width < 1 || s.width > 16384 || s.height < 1 || s.height > 16384)
        throw InputError("image size must be 1..16384 pixels per side, got " +
                         std::to_string(s.width) + "x" + std::to_string(s.height));
    if (s.spp < 1 || s.spp > 65536)
        throw InputError("samples per pixel must be 1..65536, got " + std::to_string(s.spp));
}

/// Lambertian response to a light at the eye, plus the material's emission.
glm::vec3 shade(const Scene& scene, const Ray& ray, const Hit& hit) {
    if (!hit.hit()) return glm::vec3(0.0f);
    const glm::vec3 normal = glm::normalize(geometric_normal(scene.corners(std::size_t(hit.prim))));
    const float cosine = std::abs(glm::dot(normal, ray.dir));
    const Material& material = scene.materials[scene.triangle_materials[std::size_t(hit.prim)]];
    return material.kd * cosine + glm::min(material.ke, glm::vec3(1.0f));
}

}  // namespace

EyeLightResult render_eye_light(const Scene& scene, const Camera& camera, Tracer& tracer,
                                const EyeLightSettings& settings) {
    validate(settings);
    const PinholeProjection projection(camera, settings.width, settings.height);
    const std::size_t pixel_count = std::size_t(settings.width) * std::size_t(settings.height);
    std::vector<Ray> rays(pixel_count);
    std::vector<Hit> hits(pixel_count);
    EyeLightResult result{Image(settings.width, settings.height), {}, 0.0};
    const tbb::blocked_range<std::size_t> all_pixels(0, pixel_count, 1024);

    for (int sample = 0; sample < settings.spp; ++sample) {
        tbb::parallel_for(all_pixels, [&](const auto& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const int x = int(i % std::size_t(settings.width));
                const int y = int(i / std::size_t(settings.width));
                float jx = 0.5f, jy = 0.5f;
                if (settings.spp > 1) {
                    const std::uint32_t h = hash_combine(
                        hash_combine(settings.seed, std::uint32_t(i)), std::uint32_t(sample));
                    jx = hash_to_unit_float(h);
                    jy = hash_to_unit_float(pcg_hash(h));
                }
                rays[i] = projection.ray(float(x) + jx, float(y) + jy);
            }
        });

        const auto start = std::chrono::steady_clock::now();
        result.stats += tracer.trace(rays, hits, Query::closest);
        result.trace_seconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (sample == 0 && settings.detail) {
            std::vector<Hit> again(pixel_count);
            tracer.trace(rays, again, Query::closest, settings.detail);
        }

        tbb::parallel_for(all_pixels, [&](const auto& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i)
                result.image.pixels[i] += shade(scene, rays[i], hits[i]);
        });
    }
    for (glm::vec3& p : result.image.pixels) p /= float(settings.spp);
    return result;
}

}  // namespace edacrt
