#pragma once
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace edacrt {

/// Procedural scenes, named "builtin:NAME[:key=value,...]":
///   builtin:cornell                   the Cornell box (walls, two blocks, area light), with camera
///   builtin:sphere[:subdiv=N]         closed icosphere, 20 * 4^N triangles (N <= 9, default 3)
///   builtin:cube[:n=N]                closed cube, N x N quads per face (N <= 1000, default 4)
///   builtin:soup[:count=N,seed=S,size=F]  N random triangles in [-1,1]^3, edge scale F
/// Closed meshes share vertices exactly, so they are watertight test objects.
/// Throws InputError for an unknown name, key or an out-of-range value.
Scene make_builtin_scene(std::string_view spec);

/// One line per built-in scene, for --help texts.
std::string builtin_scene_help();

}  // namespace edacrt
