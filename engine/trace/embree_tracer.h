#pragma once
#include <embree3/rtcore.h>

#include "trace/tracer.h"

namespace edacrt {

/// The industrial reference: Embree 3, its BVH built in set_scene() (per frame) with the robust
/// (watertight) flag, traced with rtcIntersect1 / rtcOccluded1 over rays in parallel.
class EmbreeTracer final : public Tracer {
  public:
    EmbreeTracer();
    ~EmbreeTracer() override;
    EmbreeTracer(const EmbreeTracer&) = delete;
    EmbreeTracer& operator=(const EmbreeTracer&) = delete;

    Method method() const override { return Method::embree; }
    void set_scene(const Scene& scene) override;

  protected:
    TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                           TraceDetail* detail) override;

  private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

}  // namespace edacrt
