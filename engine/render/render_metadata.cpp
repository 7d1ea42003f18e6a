#include "render/render_metadata.h"

#include "util/exact_text.h"

namespace edacrt {

ImageMetadata render_metadata(const RenderDescription& r) {
    return {{"software", "EDACRT Studio (" + r.software + ")"},
            {"scene", r.scene},
            {"method", r.method},
            {"integrator", r.integrator},
            {"spp", std::to_string(r.spp)},
            {"seed", std::to_string(r.seed)},
            {"renderSeconds", exact_text(r.seconds)},
            {"cameraEye", exact_text(r.camera.eye)},
            {"cameraLookAt", exact_text(r.camera.look_at)},
            {"cameraUp", exact_text(r.camera.up)},
            {"cameraVerticalFovDegrees", exact_text(r.camera.vfov_degrees)}};
}

}  // namespace edacrt
