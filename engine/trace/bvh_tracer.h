#pragma once
#include <cstdint>
#include <vector>

#include "geometry/aabb.h"
#include "trace/tracer.h"

namespace edacrt {

/// Baseline with a stored structure: a binned-SAH BVH (Wald, "On fast Construction of
/// SAH-based Bounding Volume Hierarchies", 2007), built in set_scene() (per frame), traversed
/// per ray with a stack, nearer child first.
class BvhTracer final : public Tracer {
  public:
    Method method() const override { return Method::bvh; }
    void set_scene(const Scene& scene) override;
    std::size_t working_bytes() const override;

    /// A node is a leaf when count > 0 (triangles prims[first, first + count)); otherwise its
    /// children are nodes first and first + 1.
    struct Node {
        Aabb box;
        std::uint32_t first = 0;
        std::uint32_t count = 0;
    };
    const std::vector<Node>& nodes() const { return nodes_; }

  protected:
    TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                           TraceDetail* detail) override;

  private:
    template <Query Q>
    TraceStats trace_all(std::span<const Ray> rays, std::span<Hit> hits, RayStats* ray_stats) const;

    std::vector<Triangle> triangles_;
    std::vector<std::uint32_t> prims_;  // triangle numbers, grouped by leaf
    std::vector<Node> nodes_;
    std::size_t build_bytes_ = 0;  // the builder's temporaries, alive beside the members
};

}  // namespace edacrt
