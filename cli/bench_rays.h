#pragma once
// The ray sets of `edacrt bench`, all from one camera. Random numbers are counter-based
// (render/benchmark_rays.h): a ray depends only on the seed, its pixel and its sample, and
// camera and diffuse rays equal those of bench/paper_rays.cpp for the same view, size and seed.
#include <cstdint>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/tracer.h"
#include "util/enum_table.h"

namespace edacrt::cli {

enum class RaySetKind { camera, diffuse, ao, shadow };
inline constexpr auto kRaySetKinds = enum_table<RaySetKind>(
    "ray set", {{RaySetKind::camera, "camera", "--spp jittered rays per pixel, closest hit"},
                {RaySetKind::diffuse, "diffuse", "a cosine bounce from each camera hit, closest"},
                {RaySetKind::ao, "ao", "diffuse, up to 5% of the diagonal, any hit"},
                {RaySetKind::shadow, "shadow", "from each camera hit to a light, any hit"}});

/// AO rays reach this fraction of the scene's diagonal.
inline constexpr float kAoDistanceFraction = 0.05f;

class BenchRays {
  public:
    /// Traces the 1-spp camera rays once (bvh, untimed): the secondary sets start at their hits.
    BenchRays(const Scene& scene, const Camera& camera, int width, int height, std::uint32_t seed);

    /// spp jittered rays per pixel, a pixel's samples together, rows from the top; closest hit.
    std::vector<Ray> camera(int spp) const;
    /// One cosine-distributed ray about the geometric normal from every camera hit; closest.
    std::vector<Ray> diffuse() const;
    /// Like diffuse() but up to kAoDistanceFraction of the diagonal; any hit.
    std::vector<Ray> ambient_occlusion() const;
    /// From every camera hit to a random point on an emitter (chosen by power), or, without
    /// emitters, to a point light a tenth of the scene's height above its top; any hit.
    std::vector<Ray> shadow() const;

    const char* light() const { return emitters_ ? "emissive triangles" : "point light above"; }

  private:
    template <class MakeRay>
    std::vector<Ray> from_hits(MakeRay make_ray) const;

    const Scene& scene_;
    PinholeProjection projection_;
    int width_, height_;
    std::uint32_t seed_;
    std::vector<Ray> camera_;  // 1 spp
    std::vector<Hit> hits_;
    bool emitters_;
};

}  // namespace edacrt::cli
