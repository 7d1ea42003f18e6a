#pragma once
// One batch of a render's first pass, taken as the renderer traces it, so that the viewer (and a
// test) can record its recursion: the camera rays, a bounce's rays, a bounce's shadow rays or the
// AO rays. Secondary batches are where sampled alpha and filter skipping decide the most.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/ray.h"
#include "render/render_settings.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace edacrt {

/// A batch of a pass. Path tracing: `camera` (bounce 0), `bounce` N >= 1 (the closest-hit rays
/// of the paths' N-th bounce), `shadow` N >= 0 (the next-event rays from the hits of bounce N,
/// 0: of the camera rays). Ambient occlusion: `camera`, `ao`. Primary shading: `camera`.
struct BatchId {
    enum class Kind : std::uint8_t { camera, bounce, shadow, ao };
    Kind kind = Kind::camera;
    int bounce = 0;

    bool operator==(const BatchId&) const = default;
};

/// "camera", "bounce:N", "shadow:N" or "ao", as the script and the JSON write it.
std::string batch_name(BatchId batch);

/// Parses batch_name()'s forms; throws InputError naming them.
BatchId parse_batch(std::string_view text);

/// Closest hit for camera and bounce rays, any hit for shadow and AO rays.
Query batch_query(BatchId batch);

/// The batches a pass of `settings` traces, in the order it traces them (path tracing: camera,
/// shadow:0, bounce:1, shadow:1, ...), bounces up to max_depth but at most `max_bounces`.
std::vector<BatchId> pass_batches(const RenderSettings& settings, int max_bounces = 64);

/// Throws InputError when `integrator` never traces `batch` (a bounce beyond max_depth, shadow
/// rays without path tracing, ...).
void check_batch(BatchId batch, const RenderSettings& settings);

/// The rays of one batch, in the order the renderer traced them (wavefront by wavefront), with
/// the image pixel (y * width + x) each belongs to.
struct CapturedBatch {
    BatchId id;
    std::vector<Ray> rays;
    std::vector<std::uint32_t> pixels;
};

/// Renders the first pass (one sample per pixel, as the viewer's first pass and its statistics)
/// of `settings` with `tracer` (given `scene`) and returns batch `id`; empty when the pass made
/// no such rays (every path ended before that bounce). Throws InputError as check_batch() does,
/// and for bad settings or camera.
CapturedBatch capture_batch(const Scene& scene, Tracer& tracer, const Camera& camera,
                            RenderSettings settings, BatchId id);

}  // namespace edacrt
