// Unidirectional path tracing as a wavefront: every bounce of every path of the tile is one
// closest-hit batch, and the next-event (shadow) rays of that bounce one any-hit batch.
// Emitters are sampled by power (lights.h) and combined with BSDF sampling by multiple
// importance sampling (power heuristic, Veach 1997); paths end by Russian roulette or at
// max_depth. Scenes without emitters are lit by a uniform sky that paths reach by escaping.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "render/wavefront.h"

namespace edacrt {
namespace {

float power_heuristic(float pdf, float other_pdf) {
    const float a = pdf * pdf, b = other_pdf * other_pdf;
    return a + b > 0.0f ? a / (a + b) : 0.0f;
}

float max_component(glm::vec3 v) { return std::max({v.x, v.y, v.z}); }

// Sample dimension pairs: 0 is the pixel jitter; bounce d uses kPairsPerBounce from 1 + 4 d.
constexpr std::uint32_t kPairsPerBounce = 4;

}  // namespace

bool render_path(Wavefront& wf, std::size_t begin, std::size_t end, std::span<glm::vec3> radiance) {
    const Scene& scene = wf.scene;
    const Lights& lights = wf.shading.lights;
    const RenderSettings& settings = wf.settings;

    WavefrontBuffers& b = wf.buffers;
    std::vector<Ray>& rays = b.rays;
    wf.camera_rays(begin, end, rays);
    std::vector<PathState>& paths = b.paths;
    paths.assign(rays.size(), PathState{});
    for (std::size_t i = 0; i < paths.size(); ++i) paths[i].pixel = std::uint32_t(i);
    std::fill(radiance.begin(), radiance.end(), glm::vec3(0.0f));

    std::vector<Hit>& hits = b.hits;
    std::vector<Ray>&next_rays = b.next_rays, &shadow_rays = b.secondary_slots;
    std::vector<glm::vec3>& shadow_light = b.shadow_light;
    std::vector<std::uint8_t>&alive = b.alive, &has_shadow = b.has_shadow;
    for (int depth = 0; !paths.empty(); ++depth) {
        hits.resize(rays.size());
        const BatchId id{depth == 0 ? BatchId::Kind::camera : BatchId::Kind::bounce, depth};
        if (!wf.trace(id, rays, hits, [&](std::size_t i) { return begin + paths[i].pixel; }))
            return false;
        const std::size_t n = rays.size();
        next_rays.resize(n);
        shadow_rays.resize(n);
        shadow_light.resize(n);
        alive.assign(n, 0);
        has_shadow.assign(n, 0);

        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const auto& range) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                PathState& path = paths[i];
                const Ray& ray = rays[i];
                const Hit& hit = hits[i];
                glm::vec3& pixel_radiance = radiance[path.pixel];
                if (!hit.hit()) {
                    if (lights.empty()) pixel_radiance += path.throughput * settings.sky;
                    continue;
                }
                const Surface s = make_surface(scene, ray, hit);
                const Material& material = scene.materials[s.material];
                if (material.emissive() && glm::dot(s.ng_stored, ray.dir) < 0.0f) {
                    float weight = 1.0f;
                    if (path.bsdf_pdf > 0.0f) {
                        const float cosine = -glm::dot(s.ng_stored, ray.dir);
                        const float light_pdf =
                            lights.pdf_area(std::uint32_t(hit.prim)) * hit.t * hit.t / cosine;
                        weight = power_heuristic(path.bsdf_pdf, light_pdf);
                    }
                    pixel_radiance += path.throughput * material.ke * weight;
                }
                if (depth == settings.max_depth) continue;

                const Bsdf bsdf = wf.shading.bsdf(s);
                const PixelSampler sampler = wf.sampler(begin + path.pixel);
                const std::uint32_t pair = 1 + kPairsPerBounce * std::uint32_t(depth);
                const glm::vec2 u_choice = sampler.get_2d(pair);  // light, lobe
                const glm::vec3 wo = -ray.dir;

                // Next-event estimation: one point on an emitter, MIS-weighted against the BSDF.
                if (!bsdf.is_delta() && !lights.empty()) {
                    const LightSample light =
                        lights.sample(scene, u_choice.x, sampler.get_2d(pair + 1));
                    const glm::vec3 to_light = light.point - s.point.p;
                    const float distance2 = glm::dot(to_light, to_light);
                    const glm::vec3 wi = to_light / std::sqrt(distance2);
                    const float light_cosine = -glm::dot(light.normal, wi);  // front side only
                    const float cosine = glm::dot(s.ns, wi);
                    if (distance2 > 0.0f && light_cosine > 0.0f && cosine > 0.0f &&
                        glm::dot(s.ng, wi) > 0.0f) {
                        const BsdfEval eval = evaluate(bsdf, s.ns, wo, wi);
                        const float light_pdf = light.pdf_area * distance2 / light_cosine;
                        if (eval.pdf > 0.0f && light_pdf > 0.0f) {
                            shadow_light[i] =
                                path.throughput * eval.f * light.radiance *
                                (cosine * power_heuristic(light_pdf, eval.pdf) / light_pdf);
                            shadow_rays[i] = spawn_ray_to(s, light.point);
                            has_shadow[i] = 1;
                        }
                    }
                }

                // Continue the path by sampling the BSDF.
                const auto sampled =
                    sample(bsdf, s.ns, s.ng_stored, wo, u_choice.y, sampler.get_2d(pair + 2));
                if (!sampled) continue;
                const bool transmits = glm::dot(sampled->wi, s.ng) < 0.0f;
                if (transmits && bsdf.kind != Bsdf::Kind::dielectric) continue;
                path.throughput *= sampled->weight;
                if (depth + 1 >= settings.roulette_depth) {
                    const float survive = std::min(max_component(path.throughput), 0.95f);
                    if (!(sampler.get_2d(pair + 3).x < survive)) continue;
                    path.throughput /= survive;
                }
                if (!(max_component(path.throughput) > 0.0f)) continue;
                path.bsdf_pdf = sampled->delta ? 0.0f : sampled->pdf;
                next_rays[i] = spawn_ray(s, sampled->wi);
                alive[i] = 1;
            }
        });

        // One any-hit batch for the shadow rays of this bounce.
        std::vector<std::uint32_t>& shadow_index = b.indices;
        shadow_index.clear();
        for (std::size_t i = 0; i < n; ++i)
            if (has_shadow[i]) shadow_index.push_back(std::uint32_t(i));
        if (!shadow_index.empty()) {
            std::vector<Ray>& batch = b.secondary;
            batch.resize(shadow_index.size());
            for (std::size_t k = 0; k < batch.size(); ++k) batch[k] = shadow_rays[shadow_index[k]];
            std::vector<Hit>& occluders = b.secondary_hits;
            occluders.assign(batch.size(), Hit{});
            if (!wf.trace({BatchId::Kind::shadow, depth}, batch, occluders,
                          [&](std::size_t k) { return begin + paths[shadow_index[k]].pixel; }))
                return false;
            for (std::size_t k = 0; k < batch.size(); ++k)
                if (!occluders[k].hit())
                    radiance[paths[shadow_index[k]].pixel] += shadow_light[shadow_index[k]];
        }

        // Keep the paths that go on, in order (so the result does not depend on threads).
        std::size_t kept = 0;
        for (std::size_t i = 0; i < n; ++i)
            if (alive[i]) {
                paths[kept] = paths[i];
                rays[kept] = next_rays[i];
                ++kept;
            }
        paths.resize(kept);
        rays.resize(kept);
    }
    return true;
}

}  // namespace edacrt
