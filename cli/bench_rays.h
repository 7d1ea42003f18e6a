#pragma once
// The ray sets of `edacrt bench`, all from one camera. Random numbers are counter-based
// (render/benchmark_rays.h): a ray depends only on the seed, its pixel and its sample, and
// camera and diffuse rays equal those of bench/paper_rays.cpp for the same view, size and seed.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/tracer.h"
#include "util/enum_table.h"

namespace edacrt::cli {

/// camera, diffuse, ao and shadow are what --sets chooses from (kRaySetKinds); sweep is the
/// --dynamic sweep of rays per triangle.
enum class RaySetKind { camera, diffuse, ao, shadow, sweep };
inline constexpr auto kRaySetKinds = enum_table<RaySetKind>(
    "ray set", {{RaySetKind::camera, "camera", "--spp jittered rays per pixel, closest hit"},
                {RaySetKind::diffuse, "diffuse", "a cosine bounce from each camera hit, closest"},
                {RaySetKind::ao, "ao", "diffuse, up to 5% of the diagonal, any hit"},
                {RaySetKind::shadow, "shadow", "from each camera hit to a light, any hit"}});

/// One set as the reports name it.
struct RaySet {
    std::string name;  // "camera-4spp", "diffuse", "ao", "shadow", "sweep"
    RaySetKind kind = RaySetKind::camera;
    int spp = 1;                   // camera
    double rays_per_triangle = 0;  // sweep

    /// Any hit for ao and shadow, else closest.
    Query query() const;
};

/// spp camera sets named "camera-Nspp", one per entry of `spp`.
std::vector<RaySet> camera_sets(const std::vector<int>& spp);

/// AO rays reach this fraction of the scene's diagonal.
inline constexpr float kAoDistanceFraction = 0.05f;

class BenchRays {
  public:
    BenchRays(const Scene& scene, const Camera& camera, int width, int height, std::uint32_t seed);

    /// The rays of `set`.
    std::vector<Ray> make(const RaySet& set);

    /// spp jittered rays per pixel, a pixel's samples together, rows from the top; closest hit.
    std::vector<Ray> camera(int spp) const;
    /// The 1-spp camera rays of an image of about `count` pixels, as square as whole pixels
    /// allow, seen as the width x height image is.
    std::vector<Ray> sweep(double count) const;
    /// One cosine-distributed ray about the geometric normal from every camera hit; closest.
    std::vector<Ray> diffuse();
    /// Like diffuse() but up to kAoDistanceFraction of the diagonal; any hit.
    std::vector<Ray> ambient_occlusion();
    /// From every camera hit to a random point on an emitter (chosen by power), or, without
    /// emitters, to a point light a tenth of the scene's height above its top; any hit.
    std::vector<Ray> shadow();

    const char* light() const;

  private:
    /// The secondary sets start at the hits of the 1-spp camera rays, traced once (bvh,
    /// untimed) when the first of them is made.
    template <class MakeRay>
    std::vector<Ray> from_hits(MakeRay make_ray);

    const Scene& scene_;
    Camera view_;
    int width_, height_;
    std::uint32_t seed_;
    std::vector<Ray> camera_;  // 1 spp, once traced
    std::vector<Hit> hits_;
};

}  // namespace edacrt::cli
