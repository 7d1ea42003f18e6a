// The primary integrator: camera rays only, shaded for debugging (render_settings.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "render/wavefront.h"

namespace edacrt {

bool render_primary(Wavefront& wf, std::size_t begin, std::size_t end,
                    std::span<glm::vec3> radiance) {
    std::vector<Ray>& rays = wf.buffers.rays;
    wf.camera_rays(begin, end, rays);
    std::vector<Hit>& hits = wf.buffers.hits;
    hits.assign(rays.size(), Hit{});
    if (!wf.trace({}, rays, hits, [&](std::size_t i) { return begin + i; })) return false;

    const float far = std::max(wf.shading.diagonal, 1e-30f);
    const Aabb& box = wf.shading.bounds;
    const float eye_to_far =
        box.empty() ? far
                    : glm::length(wf.projection.eye() - 0.5f * (box.lo + box.hi)) + 0.5f * far;
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const Hit& hit = hits[i];
                if (!hit.hit()) {
                    radiance[i] = glm::vec3(0.0f);
                    continue;
                }
                const Surface s = make_surface(wf.scene, rays[i], hit);
                const Material& material = wf.scene.materials[s.material];
                switch (wf.settings.primary) {
                    case PrimaryShading::eye_light:
                        radiance[i] =
                            material.kd * s.texture * std::max(glm::dot(s.ns, -rays[i].dir), 0.0f);
                        if (glm::dot(s.ng_stored, rays[i].dir) < 0.0f)  // emitters' front side
                            radiance[i] += glm::min(material.ke, glm::vec3(1.0f));
                        break;
                    case PrimaryShading::normal:
                        radiance[i] = 0.5f * s.ns + 0.5f;
                        break;
                    case PrimaryShading::albedo:
                        radiance[i] = material.kd * s.texture;
                        break;
                    case PrimaryShading::depth:
                        radiance[i] = glm::vec3(std::clamp(1.0f - hit.t / eye_to_far, 0.0f, 1.0f));
                        break;
                }
            }
        });
    return true;
}

}  // namespace edacrt
