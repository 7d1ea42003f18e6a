#pragma once
#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <vector>

#include "trace/tracer.h"

namespace edacrt {

/// The industrial reference: Embree 3, its BVH built in set_scene() (per frame) with the robust
/// (watertight) flag, traced over ranges of rays in parallel with single rays (rtcIntersect1),
/// packets of 8 (rtcIntersect8) or streams (rtcIntersect1M), as `mode` says. Embree decides
/// which triangles a ray passes through; the distances are ours (a filter accepts only
/// candidates our distance test accepts, so spawned rays do not self-intersect).
/// update_scene(dynamic) keeps a dynamic scene (RTC_SCENE_FLAG_DYNAMIC, two-level at low build
/// quality) and its buffers, rebuilding the geometry's BVH at low quality per commit;
/// update_scene(refit) the same with RTC_BUILD_QUALITY_REFIT, which refits it.
class EmbreeTracer final : public Tracer {
  public:
    explicit EmbreeTracer(EmbreeMode mode = kDefaultEmbreeMode);
    ~EmbreeTracer() override;
    EmbreeTracer(const EmbreeTracer&) = delete;
    EmbreeTracer& operator=(const EmbreeTracer&) = delete;

    Method method() const override { return Method::embree; }
    void set_scene(const Scene& scene) override;
    std::size_t working_bytes() const override;

  protected:
    UpdateWork update(const Scene& scene, SceneUpdate how) override;
    TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                           TraceDetail* detail) override;

  private:
    /// A new Embree scene for `scene`: static (rebuild) or dynamic with the build quality
    /// `how` asks for, its geometry kept for later updates.
    void build(const Scene& scene, SceneUpdate how);
    /// Whether the kept geometry has `scene`'s vertex count and corner indices.
    bool same_topology(const Scene& scene) const;
    void release();

    void trace_range(std::span<const Ray> rays, std::span<Hit> hits, Query query, std::size_t begin,
                     std::size_t end);
    /// Embree's closest hits with our distance and barycentrics (checked_hit in
    /// embree_tracer.cpp): Embree's float t of a sliver can be off by 1% where
    /// its edge functions cancel, ours is refined in double where its error bound says so.
    void refine_closest_hits(std::span<const Ray> rays, std::span<Hit> hits, std::size_t begin,
                             std::size_t end) const;

    EmbreeMode mode_;
    FrameVector<Triangle> triangles_;  // for the candidate filter (see embree_tracer.cpp)
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    RTCGeometry geometry_ = nullptr;  // scene_'s only geometry
    SceneUpdate built_for_ = SceneUpdate::rebuild;
    std::size_t vertices_ = 0;
    // What the device holds, from its memory monitor (called from Embree's threads), and the
    // most it held since set_scene() began.
    struct DeviceMemory {
        std::atomic<std::int64_t> current{0}, peak{0};
    };
    DeviceMemory device_memory_;
};

}  // namespace edacrt
