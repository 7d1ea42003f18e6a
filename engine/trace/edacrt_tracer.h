#pragma once
#include <vector>

#include "geometry/aabb.h"
#include "geometry/ray_box.h"
#include "trace/edacrt_params.h"
#include "trace/edacrt_recursion.h"
#include "trace/ray_stream.h"
#include "trace/tracer.h"

namespace edacrt {

/// Divide-and-conquer ray tracing without a stored structure: EDACRT (Nabata et al. 2013), or
/// with dacrt_params() the DACRT baseline (Afra 2012). Each batch is one recursion that splits
/// its rays and triangles, partitioning index arrays in place (no allocation per node); hits,
/// counters and statistics are the same for every thread count.
class EdacrtTracer final : public Tracer {
  public:
    explicit EdacrtTracer(const EdacrtParams& params = {}, Method method = Method::edacrt);

    Method method() const override { return method_; }
    void set_scene(const Scene& scene) override;
    std::size_t working_bytes() const override;

    const EdacrtParams& params() const { return params_; }
    /// Throws InputError for parameters out of range (see validate()).
    void set_params(const EdacrtParams& params);

    /// Per-batch data, kept between batches to avoid reallocating.
    struct BatchBuffers {
        RayStreamStorage rays;
        FrameVector<std::uint32_t> tris;
        RecursionScratches scratch;  // per thread: partitions, binning, sampling, leaves
    };

  protected:
    UpdateWork update(const Scene& scene, SceneUpdate how) override;
    TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                           TraceDetail* detail) override;

  private:
    template <Query Q>
    TraceStats trace_with(std::span<const Ray> rays, std::span<Hit> hits, TraceDetail* detail);

    /// The recursion's triangles from triangles_: each one, or its pieces (params_.presplit).
    /// With `scene`, triangles_ is gathered from it in the same pass.
    void prepare_triangles(const Scene* scene = nullptr);
    /// The threads' scratch (per thread: O(triangles) for the triangle partitions).
    std::size_t scratch_bytes() const;

    EdacrtParams params_;
    Method method_;
    FrameVector<Triangle> triangles_;  // the scene's, in scene order
    FrameVector<float> areas_;         // their boxes' areas, for the pre-split plan
    EdacrtScene scene_;
    FrameVector<std::uint32_t> references_;  // the slots of scene_ in use, in order
    BatchBuffers batch_;
};

}  // namespace edacrt
