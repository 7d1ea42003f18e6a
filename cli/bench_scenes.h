#pragma once
// Which scenes `edacrt bench` measures, and from where it looks at them. Names, defaults and
// interiors come from assets/scenes.json (scene/scene_manifest.h).
#include <filesystem>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/scene.h"

namespace edacrt::cli {

struct BenchScene {
    std::string name;  // as reported: a manifest name, or the file's stem
    std::string spec;  // for load_scene(): a path or builtin:...
};

/// The scenes of the manifest's list `list` ("bench", "bench_dynamic"), in order.
std::vector<std::string> bench_scene_list(const std::string& list);

/// For --help: the names of list `list` ("bunny, sponza"), or where to find them when the
/// manifest cannot be read.
std::string bench_scene_list_text(const std::string& list);

/// For --help of --scene: the manifest's scene names and the list "bench".
std::string bench_scene_help();

/// Resolves each NAME_OR_PATH: a scene of the manifest by name (any case), bundled in assets/
/// or else in `scenes_dir`; else an OBJ path or builtin:... spec. A manifest scene whose file
/// is absent is skipped with a message on stderr. Throws InputError for a path that does not
/// exist, and for a scenes directory that does not exist when `scenes_dir_required` (given by
/// --scenes, or scenes named explicitly) and a scene needs it.
std::vector<BenchScene> resolve_bench_scenes(const std::vector<std::string>& names,
                                             const std::filesystem::path& scenes_dir,
                                             bool scenes_dir_required);

/// How a scene is viewed, and why.
struct BenchView {
    Camera camera;
    bool inside = false;  // an interior, looked at from inside
    std::string reason;
};

/// The benchmark's view of `scene` (named `name`). Interiors are viewed from inside: eye at a
/// sixth of the height above the floor under the box centre (the first surface straight down
/// from it), looking along the longest horizontal axis (+x or +z), 60 degrees. A scene is an
/// interior when the manifest says so of `name`, or when it is enclosed: from that eye at least
/// 95% of 256 rays in all directions hit something and at least 2/3 of those hit the front of a
/// triangle (from inside a closed object one sees back faces). Other scenes (objects) use their
/// own camera, else frame_box().
BenchView bench_view(const Scene& scene, const std::string& name);

}  // namespace edacrt::cli
