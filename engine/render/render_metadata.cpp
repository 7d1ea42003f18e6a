#include "render/render_metadata.h"

#include <cstdio>

namespace edacrt {
namespace {

/// Nine significant digits: a float reads back exactly.
std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

std::string vector(glm::vec3 v) { return number(v.x) + "," + number(v.y) + "," + number(v.z); }

}  // namespace

ImageMetadata render_metadata(const RenderDescription& r) {
    return {{"software", "EDACRT Studio (" + r.software + ")"},
            {"scene", r.scene},
            {"method", r.method},
            {"integrator", r.integrator},
            {"spp", std::to_string(r.spp)},
            {"seed", std::to_string(r.seed)},
            {"renderSeconds", number(r.seconds)},
            {"cameraEye", vector(r.camera.eye)},
            {"cameraLookAt", vector(r.camera.look_at)},
            {"cameraUp", vector(r.camera.up)},
            {"cameraVerticalFovDegrees", number(r.camera.vfov_degrees)}};
}

}  // namespace edacrt
