#include "scene_catalog.h"

#include <algorithm>
#include <string_view>

#include "scene/scene_manifest.h"
#include "scene/scene_paths.h"
#include "util/error.h"

namespace edacrt::app {
namespace {

namespace fs = std::filesystem;

constexpr const char* kBuiltins[] = {"builtin:cornell", "builtin:sphere:subdiv=5",
                                     "builtin:cube:n=8"};

/// Every file under `dir` whose name ends with `suffix`, sorted; an unreadable directory gives
/// what could be read.
std::vector<std::string> files_ending(const fs::path& dir, std::string_view suffix) {
    std::vector<std::string> list;
    std::error_code error;
    for (fs::recursive_directory_iterator it(dir, error), end; !error && it != end;
         it.increment(error))
        if (it->path().filename().string().ends_with(suffix)) list.push_back(it->path().string());
    std::sort(list.begin(), list.end());
    return list;
}

std::string with_commas(long long n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0 && digits[i - 1] != '-') out += ',';
        out += digits[i];
    }
    return out;
}

/// The public scenes of the manifest, or false when it cannot be read (the caller falls back
/// to listing the scenes folder).
bool add_public_scenes(const fs::path& assets, const fs::path& scenes, SceneCatalog& catalog) {
    SceneManifest manifest;
    try {
        manifest = read_scene_manifest(assets / "scenes.json");
    } catch (const InputError&) {
        return false;  // unreadable or malformed: the manifest as a whole is not trusted
    }
    std::vector<CatalogEntry> found;
    int missing = 0;
    for (const ManifestScene& scene : manifest.scenes) {
        if (is_bundled(scene, assets)) continue;
        const fs::path path = scenes / scene.folder / scene.file;
        std::error_code error;
        const bool present = fs::is_regular_file(path, error);
        found.push_back(
            {scene.folder + (present ? " (" + with_commas(scene.triangles) + " triangles)"
                                     : " (not downloaded)"),
             path.string(), present});
        missing += !present;
    }
    catalog.entries.insert(catalog.entries.end(), found.begin(), found.end());
    catalog.missing = missing;
    if (missing > 0)
        catalog.hint = std::to_string(missing) + (missing == 1 ? " more scene" : " more scenes") +
                       ": run scripts/get-scenes (see assets/SCENES.md)";
    catalog.scenes_folder = scenes.string();
    return true;
}

}  // namespace

SceneCatalog scene_catalog(const fs::path& assets, const fs::path& scenes) {
    SceneCatalog catalog;
    for (const std::string& file : files_ending(assets, ".obj"))
        catalog.entries.push_back({file, file, true});
    // Bundled animation files (scene/rigid_animation.h) name their own meshes.
    for (const std::string& file : files_ending(assets, ".anim.json"))
        catalog.entries.push_back({file + " (animated)", file, true});
    if (!add_public_scenes(assets, scenes, catalog))
        for (const std::string& file : files_ending(scenes, ".obj"))
            catalog.entries.push_back({file, file, true});
    for (const char* builtin : kBuiltins) catalog.entries.push_back({builtin, builtin, true});
    return catalog;
}

SceneCatalog scene_catalog(const fs::path& assets) {
    fs::path dir = fs::absolute(assets).lexically_normal();
    if (!dir.has_filename()) dir = dir.parent_path();  // "assets/"
    return scene_catalog(assets, default_scenes_dir(dir.parent_path()));
}

}  // namespace edacrt::app
