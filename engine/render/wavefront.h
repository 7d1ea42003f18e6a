#pragma once
// What an integrator works with while it renders one wavefront of one pass: the scene, the
// tracer (every batch of rays goes through trace()), the sample generator and the statistics.
// A pass renders `samples` samples of every pixel; its paths are numbered sample-major, path
// p being sample p / pixels of pixel p % pixels, and a wavefront is a range of them.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "render/batch_capture.h"
#include "render/render_settings.h"
#include "render/sampler.h"
#include "render/shading_scene.h"
#include "scene/camera.h"
#include "trace/tracer.h"

namespace edacrt {

/// The batches of one kind traced so far: how many, their rays and the time inside the tracer.
/// A path tracer's late bounces are small batches, where a tracer's cost per batch shows.
struct BatchTimes {
    BatchId id;
    std::uint64_t batches = 0;
    std::uint64_t rays = 0;
    double seconds = 0.0;
};

/// Counters of one pass (or, summed, of a whole render).
struct PassStats {
    TraceStats trace;                   // summed over all batches
    std::uint64_t batches = 0;          // Tracer::trace calls
    double trace_seconds = 0.0;         // inside Tracer::trace
    double seconds = 0.0;               // the whole pass
    std::uint64_t dropped_samples = 0;  // non-finite radiance replaced by black
    std::vector<BatchTimes> by_batch;   // trace_seconds by kind, in the order first traced

    void add_batch(const BatchTimes& times) {
        const auto same = std::find_if(by_batch.begin(), by_batch.end(),
                                       [&](const BatchTimes& b) { return b.id == times.id; });
        if (same == by_batch.end()) {
            by_batch.push_back(times);
            return;
        }
        same->batches += times.batches;
        same->rays += times.rays;
        same->seconds += times.seconds;
    }
    PassStats& operator+=(const PassStats& o) {
        trace += o.trace;
        batches += o.batches;
        trace_seconds += o.trace_seconds;
        seconds += o.seconds;
        dropped_samples += o.dropped_samples;
        for (const BatchTimes& b : o.by_batch) add_batch(b);
        return *this;
    }
};

/// A path of the path tracer's wavefront between bounces.
struct PathState {
    glm::vec3 throughput{1.0f};
    std::uint32_t pixel = 0;  // within the tile
    float bsdf_pdf = 0.0f;    // solid-angle pdf of the sample that made the ray; 0: camera/delta
};

/// The integrators' arrays, kept by the Renderer from wavefront to wavefront and pass to pass:
/// allocated afresh for each wavefront, their first touch (page faults) was most of a small
/// render's time outside the tracer.
struct WavefrontBuffers {
    std::vector<Ray> rays, next_rays;
    std::vector<Hit> hits;
    std::vector<PathState> paths;
    // Each bounce's secondary batch (shadow or AO rays), gathered from per-path slots.
    std::vector<Ray> secondary_slots, secondary;
    std::vector<Hit> secondary_hits;
    std::vector<glm::vec3> shadow_light;  // unoccluded contribution of each shadow ray
    std::vector<glm::vec3> albedo;        // AO: of each hit
    std::vector<std::uint8_t> alive, has_shadow;
    std::vector<std::uint32_t> indices;
};

struct Wavefront {
    const Scene& scene;
    const ShadingScene& shading;
    Tracer& tracer;
    const RenderSettings& settings;
    const PinholeProjection& projection;
    std::uint32_t first_sample;       // the sample index of the pass's first sample
    std::size_t pixels;               // width * height
    const std::atomic<bool>* cancel;  // checked before every batch
    PassStats& stats;
    WavefrontBuffers& buffers;
    CapturedBatch* capture = nullptr;  // takes the batch it names (capture_batch())

    bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }

    /// The samples of path p.
    PixelSampler sampler(std::size_t path) const {
        return PixelSampler(settings.seed, std::uint32_t(path % pixels),
                            first_sample + std::uint32_t(path / pixels));
    }

    /// Camera rays of paths [begin, end), jittered within the pixel (sample pair 0).
    void camera_rays(std::size_t begin, std::size_t end, std::vector<Ray>& rays) const;

    /// Traces batch `id` (closest or any hit as batch_query(id) says), timed; the capture
    /// takes it first if it names it, path_of(i) being the pass's path number of ray i (its
    /// pixel: path % pixels). Returns false, tracing nothing, when cancelled.
    template <class PathOf>
    bool trace(BatchId id, std::span<const Ray> rays, std::span<Hit> hits, PathOf path_of) {
        if (cancelled()) return false;
        if (capture && capture->id == id) {
            capture->rays.insert(capture->rays.end(), rays.begin(), rays.end());
            for (std::size_t i = 0; i < rays.size(); ++i)
                capture->pixels.push_back(std::uint32_t(path_of(i) % pixels));
        }
        trace_timed(id, rays, hits);
        return true;
    }

  private:
    void trace_timed(BatchId id, std::span<const Ray> rays, std::span<Hit> hits);
};

/// The camera rays of the first pass's first sample, one per pixel row by row: the batch whose
/// statistics Renderer::render_pass records (the viewer's analysis traces it again).
std::vector<Ray> first_pass_camera_rays(const Camera& camera, const RenderSettings& settings);

// The integrators: each renders paths [begin, end) of the pass into radiance[0, end - begin)
// and returns false when cancelled.
bool render_primary(Wavefront& wf, std::size_t begin, std::size_t end,
                    std::span<glm::vec3> radiance);
bool render_ao(Wavefront& wf, std::size_t begin, std::size_t end, std::span<glm::vec3> radiance);
bool render_path(Wavefront& wf, std::size_t begin, std::size_t end, std::span<glm::vec3> radiance);

}  // namespace edacrt
