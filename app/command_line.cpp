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

/// A scene file's absolute path, so the line runs from any folder; built-in scenes as they are.
std::string absolute_scene(const std::string& scene) {
    if (scene.empty() || scene.starts_with("builtin:")) return scene;
    std::error_code error;
    const std::filesystem::path path = std::filesystem::absolute(scene, error);
    return error ? scene : path.lexically_normal().string();
}

}  // namespace

std::filesystem::path this_executable() {
    std::error_code error;
    std::filesystem::path path = std::filesystem::read_symlink("/proc/self/exe", error);
    return error ? std::filesystem::path() : path;
}

std::string edacrt_program(const std::filesystem::path& viewer) {
    if (viewer.empty()) return "edacrt";
    const std::filesystem::path beside = viewer.parent_path() / "edacrt";
    std::error_code error;
    return std::filesystem::is_regular_file(beside, error) && beside.is_absolute()
               ? beside.lexically_normal().string()
               : "edacrt";
}

std::string render_command_line(const ViewCommand& v) {
    const RenderSettings& s = v.settings;
    const std::string scene = shell_quoted(absolute_scene(v.scene));
    std::string line = shell_quoted(v.program) + " render";
    if (!v.animated || v.animation.empty())
        line += (v.animated ? " --animate " : " --scene ") + scene;
    else
        line += " --scene " + scene + " --animate " + shell_quoted(v.animation);
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
