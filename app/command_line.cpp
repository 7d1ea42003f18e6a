#include "command_line.h"

#include <string_view>

#include "util/exact_text.h"

namespace edacrt::app {
namespace {

/// Quotes a shell word unless it is made only of safe characters.
std::string shell_quoted(std::string_view word) {
    const bool safe = !word.empty() && word.find_first_not_of(
                                           "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                           "0123456789_-+=./:,@%") == std::string_view::npos;
    if (safe) return std::string(word);
    std::string out = "'";
    for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

std::string render_command_line(const ViewCommand& v) {
    const RenderSettings& s = v.settings;
    std::string line = "edacrt render";
    if (!v.animated || v.animation.empty())
        line += (v.animated ? " --animate " : " --scene ") + shell_quoted(v.scene);
    else
        line += " --scene " + shell_quoted(v.scene) + " --animate " + shell_quoted(v.animation);
    if (v.animated) {
        line += " --time " + exact_text(v.time) + " --update " +
                std::string(enum_name(kSceneUpdates, v.update));
        if (v.shutter > 0.0) line += " --shutter " + exact_text(v.shutter);
    }
    line += " --method " + std::string(enum_name(kMethods, v.method));
    if (v.method == Method::embree && v.embree_mode != kDefaultEmbreeMode)
        line += " --embree-mode " + std::string(enum_name(kEmbreeModes, v.embree_mode));
    line += " --integrator " + std::string(enum_name(kIntegrators, s.integrator));
    if (s.integrator == Integrator::primary)
        line += " --primary " + std::string(enum_name(kPrimaryShadings, s.primary));
    if (s.integrator == Integrator::path) line += " --max-depth " + std::to_string(s.max_depth);
    if (s.integrator == Integrator::ao) line += " --ao-samples " + std::to_string(s.ao_samples);
    line += " --spp " + std::to_string(v.spp) + " --width " + std::to_string(s.width) +
            " --height " + std::to_string(s.height) + " --seed " + std::to_string(s.seed);
    line += " --eye " + exact_text(v.camera.eye) + " --look-at " + exact_text(v.camera.look_at) +
            " --up " + exact_text(v.camera.up) + " --fov " + exact_text(v.camera.vfov_degrees);
    if (v.exposure != 0.0f) line += " --exposure " + exact_text(v.exposure);
    if (v.tone_map != ToneMap::clamp)
        line += " --tone-map " + std::string(enum_name(kToneMaps, v.tone_map));
    const EdacrtParams defaults;
    for (const ParamInfo& info : edacrt_param_info())
        if (info.get(v.params) != info.get(defaults))
            line += " --" + std::string(info.key) + " " + shell_quoted(param_text(v.params, info));
    return line + " --out " + shell_quoted(v.out);
}

}  // namespace edacrt::app
