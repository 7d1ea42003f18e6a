#include "bench_rays.h"

#include <cmath>
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

Query RaySet::query() const {
    return kind == RaySetKind::ao || kind == RaySetKind::shadow ? Query::any : Query::closest;
}

std::vector<RaySet> camera_sets(const std::vector<int>& spp) {
    std::vector<RaySet> sets;
    for (const int n : spp)
        sets.push_back({"camera-" + std::to_string(n) + "spp", RaySetKind::camera, n});
    return sets;
}

BenchRays::BenchRays(const Scene& scene, const Camera& camera, int width, int height,
                     std::uint32_t seed)
    : scene_(scene), view_(camera), width_(width), height_(height), seed_(seed) {}

std::vector<Ray> BenchRays::make(const RaySet& set) {
    switch (set.kind) {
        case RaySetKind::camera:
            return camera(set.spp);
        case RaySetKind::diffuse:
            return diffuse();
        case RaySetKind::ao:
            return ambient_occlusion();
        case RaySetKind::shadow:
            return shadow();
        case RaySetKind::sweep:
            return sweep(set.rays_per_triangle * double(scene_.triangle_count()));
    }
    return {};
}

std::vector<Ray> BenchRays::camera(int spp) const {
    return jittered_camera_rays(PinholeProjection(view_, width_, height_), width_, height_, spp,
                                seed_);
}

std::vector<Ray> BenchRays::sweep(double count) const {
    const int width = std::max(1, int(std::lround(std::sqrt(count))));
    const int height = std::max(1, int(std::lround(count / width)));
    return jittered_camera_rays(PinholeProjection(view_, width, height), width, height, 1, seed_);
}

const char* BenchRays::light() const {
    return Lights(scene_).empty() ? "point light above" : "emissive triangles";
}

template <class MakeRay>
std::vector<Ray> BenchRays::from_hits(MakeRay make_ray) {
    if (camera_.empty()) {
        camera_ = camera(1);
        hits_.resize(camera_.size());
        const auto tracer = make_tracer(Method::bvh);
        tracer->set_scene(scene_);
        tracer->trace(camera_, hits_, Query::closest);
    }
    std::vector<Ray> rays;
    for (std::size_t i = 0; i < camera_.size(); ++i)
        if (hits_[i].hit())
            rays.push_back(make_ray(make_surface(scene_, camera_[i], hits_[i]), std::uint32_t(i)));
    return rays;
}

std::vector<Ray> BenchRays::diffuse() {
    return from_hits([&](const Surface& s, std::uint32_t pixel) {
        const glm::vec2 u = random_2d(sample_key(seed_, kBounceStream, pixel, 1));
        return spawn_ray(s, sample_cosine_hemisphere(s.ng, u));
    });
}

std::vector<Ray> BenchRays::ambient_occlusion() {
    const Aabb box = scene_.bounds();
    const float reach = kAoDistanceFraction * glm::length(box.hi - box.lo);
    return from_hits([&](const Surface& s, std::uint32_t pixel) {
        const glm::vec2 u = random_2d(sample_key(seed_, kAoStream, pixel, 0));
        return spawn_ray(s, sample_cosine_hemisphere(s.ng, u), reach);
    });
}

std::vector<Ray> BenchRays::shadow() {
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
