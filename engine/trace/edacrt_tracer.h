#pragma once
#include <vector>

#include "geometry/aabb.h"
#include "geometry/ray_box.h"
#include "trace/edacrt_params.h"
#include "trace/tracer.h"

namespace edacrt {

/// Divide-and-conquer ray tracing without a stored structure: EDACRT (Nabata et al. 2013), or
/// with dacrt_params() the DACRT baseline (Afra 2012). Each batch recursively splits its
/// rays and triangles, partitioning index arrays in place (no allocation per node).
class EdacrtTracer final : public Tracer {
  public:
    explicit EdacrtTracer(const EdacrtParams& params = {}, Method method = Method::edacrt);

    Method method() const override { return method_; }
    void set_scene(const Scene& scene) override;

    const EdacrtParams& params() const { return params_; }
    /// Throws InputError for parameters out of range (see validate()).
    void set_params(const EdacrtParams& params);

    /// Per-frame triangle data, in scene order.
    struct SceneData {
        std::vector<Triangle> triangles;
        std::vector<Aabb> bounds;
        std::vector<glm::vec3> centroids;
        Aabb box;
    };

    /// Per-batch ray data, kept between batches to avoid reallocating.
    struct BatchBuffers {
        std::vector<WatertightRay> wrays;
        std::vector<SlabRay> srays;
        std::vector<float> t_far;
        std::vector<std::uint32_t> ids;
    };

  protected:
    TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                           TraceDetail* detail) override;

  private:
    template <Query Q, bool kStats>
    TraceStats trace_with(std::span<const Ray> rays, std::span<Hit> hits, TraceDetail* detail);

    EdacrtParams params_;
    Method method_;
    SceneData scene_;
    BatchBuffers batch_;
};

}  // namespace edacrt
