#include "bench_rays.h"

#include <glm/geometric.hpp>

#include "render/benchmark_rays.h"
#include "render/bsdf.h"
#include "render/shading_scene.h"
#include "util/error.h"
#include "util/hash_random.h"

namespace edacrt::cli {
namespace {

// Streams of our own, beside render/benchmark_rays.h's jitter and bounce streams.
constexpr std::uint32_t kAoStream = 0x3b5d2c47u;
constexpr std::uint32_t kLightStream = 0x5e91a0c3u;

}  // namespace

BenchRays::BenchRays(const Scene& scene, const Camera& camera, int width, int height,
                     std::uint32_t seed)
    : scene_(scene),
      projection_(camera, width, height),
      width_(width),
      height_(height),
      seed_(seed),
      camera_(this->camera(1)),
      hits_(camera_.size()),
      emitters_(!Lights(scene).empty()) {
    const auto tracer = make_tracer(Method::bvh);
    tracer->set_scene(scene);
    tracer->trace(camera_, hits_, Query::closest);
}

std::vector<Ray> BenchRays::camera(int spp) const {
    return jittered_camera_rays(projection_, width_, height_, spp, seed_);
}

template <class MakeRay>
std::vector<Ray> BenchRays::from_hits(MakeRay make_ray) const {
    std::vector<Ray> rays;
    for (std::size_t i = 0; i < camera_.size(); ++i)
        if (hits_[i].hit())
            rays.push_back(make_ray(make_surface(scene_, camera_[i], hits_[i]), std::uint32_t(i)));
    return rays;
}

std::vector<Ray> BenchRays::diffuse() const {
    return from_hits([&](const Surface& s, std::uint32_t pixel) {
        const glm::vec2 u = random_2d(sample_key(seed_, kBounceStream, pixel, 1));
        return spawn_ray(s, sample_cosine_hemisphere(s.ng, u));
    });
}

std::vector<Ray> BenchRays::ambient_occlusion() const {
    const Aabb box = scene_.bounds();
    const float reach = kAoDistanceFraction * glm::length(box.hi - box.lo);
    return from_hits([&](const Surface& s, std::uint32_t pixel) {
        const glm::vec2 u = random_2d(sample_key(seed_, kAoStream, pixel, 0));
        return spawn_ray(s, sample_cosine_hemisphere(s.ng, u), reach);
    });
}

std::vector<Ray> BenchRays::shadow() const {
    const Lights lights(scene_);
    const Aabb box = scene_.bounds();
    const glm::vec3 above{0.5f * (box.lo.x + box.hi.x), box.hi.y + 0.1f * (box.hi.y - box.lo.y),
                          0.5f * (box.lo.z + box.hi.z)};
    return from_hits([&](const Surface& s, std::uint32_t pixel) {
        if (lights.empty()) return spawn_ray_to(s, above);
        const glm::vec2 u = random_2d(sample_key(seed_, kLightStream, pixel, 0));
        const float select = hash_to_unit_float(sample_key(seed_, kLightStream, pixel, 1));
        return spawn_ray_to(s, lights.sample(scene_, select, u).point);
    });
}

}  // namespace edacrt::cli
