#include "scene/builtin_scenes.h"
#include "scene/obj_loader.h"
#include "scene/scene.h"

namespace edacrt {

Scene load_scene(const std::string& spec) {
    if (spec.starts_with("builtin:")) return make_builtin_scene(spec);
    return load_obj(spec);
}

}  // namespace edacrt
