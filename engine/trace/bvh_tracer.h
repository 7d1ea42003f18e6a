#pragma once
#include <cstdint>
#include <vector>

#include "trace/bvh_build.h"
#include "trace/bvh_wide.h"
#include "trace/tracer.h"

namespace edacrt {

/// Baseline with a stored structure: a binned-SAH BVH (Wald 2007, bvh_build.h) built in
/// set_scene() (per frame) and collapsed to 8 children per node (bvh_wide.h); traversed per ray
/// with a stack, nearest child first, skipping children that start beyond the nearest hit so far.
/// update_scene(refit) keeps the tree and refits its boxes to the triangles' new positions.
class BvhTracer final : public Tracer {
  public:
    explicit BvhTracer(const BvhBuildOptions& options = {}) : options_(options) {}

    Method method() const override { return Method::bvh; }
    void set_scene(const Scene& scene) override;
    std::size_t working_bytes() const override;

    const std::vector<Bvh8Node>& nodes() const { return wide_; }
    /// The triangle of each reference, grouped by leaf.
    const std::vector<std::uint32_t>& prims() const { return bvh_prims_; }

  protected:
    UpdateWork update(const Scene& scene, SceneUpdate how) override;
    TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                           TraceDetail* detail) override;

  private:
    /// The tree kept, every box recomputed from the triangles of `scene` (same count) as the
    /// build computes them, so the hits stay exact.
    void refit(const Scene& scene);

    /// The batch, counting per ray through `observer` (ray_observer.h).
    template <Query Q, class Observer>
    TraceStats trace_all(std::span<const Ray> rays, std::span<Hit> hits,
                         const Observer& observer) const;

    BvhBuildOptions options_;
    std::vector<Bvh8Node> wide_;
    std::vector<std::uint32_t> bvh_prims_;
    std::vector<Triangle> leaf_triangles_;  // the triangle of each reference, in prims order
    std::size_t build_bytes_ = 0;           // the builder's temporaries, alive beside the members
};

}  // namespace edacrt
