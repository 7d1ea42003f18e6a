#pragma once
// Eye-light rendering of primary rays: every pixel is lit by a light at the camera, the
// simplest shading that shows geometry and materials. One batch of camera rays per sample.
#include <cstdint>

#include "render/image.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace edacrt {

struct EyeLightSettings {
    int width = 512;
    int height = 512;
    int spp = 1;             // samples per pixel; 1 samples pixel centres, more are jittered
    std::uint32_t seed = 0;  // jitter seed
    // When set, receives the statistics of the first sample's camera rays (one ray per pixel),
    // from an extra pass that is not part of trace_seconds.
    TraceDetail* detail = nullptr;
};

struct EyeLightResult {
    Image image;
    TraceStats stats;          // summed over all samples
    double trace_seconds = 0;  // time inside Tracer::trace only
};

/// The tracer must have been given `scene` with set_scene(). Throws InputError for settings
/// out of range.
EyeLightResult render_eye_light(const Scene& scene, const Camera& camera, Tracer& tracer,
                                const EyeLightSettings& settings);

}  // namespace edacrt
