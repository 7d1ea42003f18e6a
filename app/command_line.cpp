#include "command_line.h"

#include <cstdio>
#include <string_view>

namespace edacrt::app {
namespace {

/// Quotes a shell word unless it is made only of safe characters.
std::string quoted(std::string_view word) {
    const bool safe = !word.empty() && word.find_first_not_of(
                                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                           "0123456789_-+=./:,@%") == std::string_view::npos;
    if (safe) return std::string(word);
    std::string out = "'";
    for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

/// %.9g: nine significant digits read back to the same float.
std::string exact(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(v));
    return text;
}

/// %.17g: seventeen significant digits read back to the same double.
std::string exact(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

std::string exact(const glm::vec3& v) { return exact(v.x) + "," + exact(v.y) + "," + exact(v.z); }

}  // namespace

std::string render_command_line(const ViewCommand& v) {
    const RenderSettings& s = v.settings;
    std::string line = "edacrt render";
    if (!v.animated || v.animation.empty())
        line += (v.animated ? " --animate " : " --scene ") + quoted(v.scene);
    else
        line += " --scene " + quoted(v.scene) + " --animate " + quoted(v.animation);
    if (v.animated) {
        line +=
            " --time " + exact(v.time) + " --update " + std::string(scene_update_name(v.update));
        if (v.shutter > 0.0) line += " --shutter " + exact(v.shutter);
    }
    line += " --method " + std::string(method_name(v.method));
    if (v.method == Method::embree && v.embree_mode != kDefaultEmbreeMode)
        line += " --embree-mode " + std::string(embree_mode_name(v.embree_mode));
    line += " --integrator " + std::string(integrator_name(s.integrator));
    if (s.integrator == Integrator::primary)
        line += " --primary " + std::string(primary_shading_name(s.primary));
    if (s.integrator == Integrator::path) line += " --max-depth " + std::to_string(s.max_depth);
    if (s.integrator == Integrator::ao) line += " --ao-samples " + std::to_string(s.ao_samples);
    line += " --spp " + std::to_string(v.spp) + " --width " + std::to_string(s.width) +
            " --height " + std::to_string(s.height) + " --seed " + std::to_string(s.seed);
    line += " --eye " + exact(v.camera.eye) + " --look-at " + exact(v.camera.look_at) + " --up " +
            exact(v.camera.up) + " --fov " + exact(v.camera.vfov_degrees);
    if (v.exposure != 0.0f) line += " --exposure " + exact(v.exposure);
    if (v.tone_map != "clamp") line += " --tone-map " + v.tone_map;
    const EdacrtParams defaults;
    for (const ParamInfo& info : edacrt_param_info())
        if (info.get(v.params) != info.get(defaults))
            line += " --" + std::string(info.key) + " " + quoted(param_text(v.params, info));
    return line + " --out " + quoted(v.out);
}

}  // namespace edacrt::app
