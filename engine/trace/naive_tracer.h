#pragma once
#include <vector>

#include "trace/tracer.h"

namespace edacrt {

/// The reference: every ray against every triangle, rays spread over threads with oneTBB.
class NaiveTracer final : public Tracer {
  public:
    Method method() const override { return Method::naive; }
    void set_scene(const Scene& scene) override;
    std::size_t working_bytes() const override { return triangles_.capacity() * sizeof(Triangle); }

  protected:
    UpdateWork update(const Scene& scene, SceneUpdate how) override;
    TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                           TraceDetail* detail) override;

  private:
    FrameVector<Triangle> triangles_;
};

}  // namespace edacrt
