#pragma once
// Rigid motion of several objects with keyframed transforms, from a small JSON file.
#include <filesystem>

#include "scene/animation.h"

namespace edacrt {

/// Loads a file such as assets/animations/spot-teapot.anim.json:
///   {"camera": {"eye": [x, y, z], "look_at": [x, y, z], "up": [0, 1, 0], "fov": 40},
///    "objects": [
///      {"mesh": "../spot/spot.obj",
///       "keys": [{"time": 0, "translate": [0, 0, 0], "rotate": [0, 1, 0, 0], "scale": 1},
///                {"time": 4, "rotate": [0, 1, 0, 360], "scale": [1, 2, 1]}]},
///      {"mesh": "builtin:cube:n=1"}]}
/// "mesh" is an OBJ path relative to the file, or a builtin: scene. A point p of a mesh goes to
/// translate + R (scale * p), R the rotation by the degrees about the axis (right-handed); a
/// key's omitted transforms are the identity, an object without keys stays as loaded, key
/// times start at 0 or later and increase. Between two keys translation and scale go
/// linearly; a rotation about the same axis goes by its angle linearly (0 to 360 degrees is a
/// whole turn), otherwise by quaternion slerp along the shorter arc. Before the first key and
/// after the last the nearest key holds; duration() is the last key's time. The camera is
/// optional. The objects form one scene in file order (triangles, materials, normals
/// appended). Throws InputError naming the file and the entry that is wrong.
AnimatedScene load_rigid_animation(const std::filesystem::path& path);

}  // namespace edacrt
