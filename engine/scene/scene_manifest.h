#pragma once
// assets/scenes.json, the one list of the project's scenes: every public scene (three of them
// also bundled in assets/), its short name, how the benchmarks view it, and the named lists of
// scenes each benchmark measures. Read here by `edacrt bench`, the viewer's scene catalog and
// bench/trace_benchmark.cpp; by bench/bench_common.py for the Python scripts; and by
// scripts/get-scenes, which fetches the files.
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace edacrt {

struct ManifestScene {
    std::string name;    // what --scene and the lists say: "name", else the folder
    std::string folder;  // under assets/ when bundled, else under the scenes folder
    std::string file;    // the scene file in `folder` ("scene")
    long long triangles = 0;
    bool interior = false;  // a building, viewed from inside by the benchmarks
};

struct SceneManifest {
    std::vector<ManifestScene> scenes;                      // in file order
    std::map<std::string, std::vector<std::string>> lists;  // "lists": name -> its "scenes"

    /// The scene called `name` (any case), or null.
    const ManifestScene* find(std::string_view name) const;

    /// The names in list `list`, in order; throws InputError when there is no such list.
    const std::vector<std::string>& list(const std::string& list) const;

    /// Every scene's name, comma-separated, in file order (for help texts).
    std::string names() const;
};

/// Reads the manifest at `path` (read_text_file(), parse_json()). Throws InputError naming the
/// file for one that cannot be read or parsed, a scene without a string "folder" or "scene", two
/// scenes of one name, or a list that names an unknown scene.
SceneManifest read_scene_manifest(const std::filesystem::path& path);

/// assets/scenes.json of the repository at `source_dir`.
std::filesystem::path scene_manifest_path(const std::filesystem::path& source_dir);

/// Whether the scene's file is bundled: present under `assets`.
bool is_bundled(const ManifestScene& scene, const std::filesystem::path& assets);

/// Its file: under `assets` when bundled, else under `scenes_dir` (present or not).
std::filesystem::path scene_file(const ManifestScene& scene, const std::filesystem::path& assets,
                                 const std::filesystem::path& scenes_dir);

}  // namespace edacrt
