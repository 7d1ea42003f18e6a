#include "scene/animation.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "scene/deformations.h"
#include "scene/obj_sequence.h"
#include "scene/rigid_animation.h"
#include "util/error.h"

namespace edacrt {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string describe(const glm::vec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%g, %g, %g", double(v.x), double(v.y), double(v.z));
    return text;
}

std::string time_text(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", t);
    return text;
}

/// Throws InputError naming the first triangle with a non-finite corner or shading normal,
/// or the first non-finite position no triangle uses. One pass over the positions when all is
/// well.
void check_finite(const Scene& scene, const std::string& spec, double t) {
    bool bad = false;
    for (const glm::vec3& p : scene.positions) bad |= !finite(p);
    for (const glm::vec3& n : scene.normals) bad |= !finite(n);
    if (!bad) return;
    const std::string where = spec + " at t = " + time_text(t) + " s: ";
    for (std::size_t i = 0; i < scene.triangle_count(); ++i)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = scene.triangles[i][k];
            if (!finite(scene.positions[v]))
                throw InputError(where + "triangle " + std::to_string(i) +
                                 " has a non-finite corner (vertex " + std::to_string(v) + ": " +
                                 describe(scene.positions[v]) + ")");
            if (scene.triangle_normals.empty() || scene.triangle_normals[i][k] < 0) continue;
            const auto n = std::size_t(scene.triangle_normals[i][k]);
            if (!finite(scene.normals[n]))
                throw InputError(where + "triangle " + std::to_string(i) +
                                 " has a non-finite shading normal (" + describe(scene.normals[n]) +
                                 ")");
        }
    for (std::size_t v = 0; v < scene.positions.size(); ++v)
        if (!finite(scene.positions[v]))
            throw InputError(where + "vertex " + std::to_string(v) + " is not finite (" +
                             describe(scene.positions[v]) + ")");
    throw InputError(where + "a shading normal no triangle uses is not finite");
}

}  // namespace

Animation::Animation(std::string spec, const Scene& scene)
    : spec_(std::move(spec)),
      positions_(scene.positions.size()),
      normals_(scene.normals.size()),
      triangles_(scene.triangles.size()) {}

void Animation::frame(double t, Scene& scene) {
    if (!std::isfinite(t))
        throw InputError(spec_ + ": the time must be a finite number of seconds, got " +
                         time_text(t));
    if (scene.positions.size() != positions_ || scene.normals.size() != normals_ ||
        scene.triangles.size() != triangles_)
        throw std::invalid_argument("Animation::frame: " + scene.source +
                                    " is not the scene this animation was made with (" +
                                    std::to_string(scene.triangles.size()) + " triangles, " +
                                    std::to_string(triangles_) + " expected)");
    write_frame(t, scene);
    check_finite(scene, spec_, t);
}

AnimatedScene load_animated_scene(const std::string& scene_spec,
                                  const std::string& animation_spec) {
    const bool own_scene = animation_has_geometry(animation_spec);
    if (own_scene && !scene_spec.empty())
        throw InputError("the animation " + animation_spec +
                         " names its own geometry; give no "
                         "scene (" +
                         scene_spec + ") with it");
    if (!own_scene && scene_spec.empty())
        throw InputError(animation_spec.empty()
                             ? "no scene given"
                             : "the animation " + animation_spec + " deforms a scene: name one");
    if (is_animation_file(animation_spec)) return load_rigid_animation(animation_spec);
    if (animation_spec.starts_with("sequence:")) return open_obj_sequence(animation_spec);
    AnimatedScene out{load_scene(scene_spec), nullptr};
    if (animation_spec.empty()) return out;
    out.animation = make_deformation(animation_spec, out.scene);
    out.animation->frame(0.0, out.scene);
    return out;
}

bool is_animation_file(std::string_view spec) {
    constexpr std::string_view kJson = ".json";
    return spec.size() >= kJson.size() &&
           std::equal(kJson.begin(), kJson.end(), spec.end() - kJson.size(), [](char a, char b) {
               return a == std::tolower(static_cast<unsigned char>(b));
           });
}

bool animation_has_geometry(std::string_view animation_spec) {
    return is_animation_file(animation_spec) || animation_spec.starts_with("sequence:");
}

std::string animation_help() {
    return "  wave[:amplitude=A,wavelength=L,period=P,axis=y,direction=x]\n"
           "      a travelling wave: corners move by up to A along `axis`, crests L apart\n"
           "      travel along `direction` (A, L: fractions of the diagonal; P: seconds)\n"
           "  twist[:angle=DEG,period=P,axis=y]\n"
           "      a twist about `axis` through the centre, swinging between +-DEG end to end\n"
           "  explode[:distance=D,period=P]\n"
           "      triangles fly apart along their normals up to D (fraction of the diagonal)\n"
           "      and back\n"
           "  FILE.json\n"
           "      objects (OBJ files, builtin: scenes) with keyframed translate/rotate/scale\n"
           "  sequence:[fps=F,]pattern=frames/name_%04d.obj\n"
           "      OBJ files as key frames, F per second (24), interpolated linearly; streamed\n";
}

}  // namespace edacrt
