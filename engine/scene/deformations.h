#pragma once
// Procedural deformations of a loaded mesh, periodic in time (animation.h has the specs).
#include <memory>
#include <string_view>

#include "scene/animation.h"

namespace edacrt {

/// The deformation `spec` names ("wave:...", "twist:...", "explode:..."), of `scene` as it is
/// now. Changes `scene`'s layout once where the deformation needs it (explode: three corners
/// of its own per triangle; wave, twist: a shading normal of its own per corner), keeping the
/// triangles, their numbers and materials. The scene is not yet at any time: call frame().
/// Throws InputError for an unknown kind or a parameter out of range, naming it.
std::unique_ptr<Animation> make_deformation(std::string_view spec, Scene& scene);

}  // namespace edacrt
