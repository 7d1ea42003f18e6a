#include "scene/animation.h"
#include "scene/builtin_scenes.h"
#include "scene/obj_loader.h"
#include "scene/scene.h"
#include "util/error.h"

namespace edacrt {

Scene load_scene(const std::string& spec) {
    if (spec.starts_with("builtin:")) return make_builtin_scene(spec);
    // Read as OBJ it would fail at its first '{', which says nothing useful.
    if (is_animation_file(spec))
        throw InputError(spec + ": an animation file, not a scene: give it with --animate");
    return load_obj(spec);
}

}  // namespace edacrt
