#pragma once
// The viewer's scene list: the OBJ files and animation files bundled in assets/, the public scenes
// of assets/scenes.json found in the scenes folder (those absent listed too, so the list can say
// how to get them), and the built-in scenes. No GL: tested headless.
#include <filesystem>
#include <string>
#include <vector>

namespace edacrt::app {

struct CatalogEntry {
    std::string label;    // what the list shows
    std::string path;     // what load_scene() takes: a file, or builtin:NAME
    bool present = true;  // false: a public scene not in the scenes folder (show it disabled)
};

struct SceneCatalog {
    // Bundled scenes (sorted), bundled animation files (*.anim.json), then the public scenes
    // (manifest order), then the built-ins.
    std::vector<CatalogEntry> entries;
    std::string hint;  // "N more scenes: run scripts/get-scenes ..." or empty
    // Where they go (the hint's tooltip: an absolute path would wrap the hint over lines as
    // many as the checkout's path is long).
    std::string scenes_folder;
    int missing = 0;  // public scenes absent from the scenes folder
};

/// The catalog for the bundled scenes under `assets` (and its manifest, assets/scenes.json)
/// and the public scenes under `scenes`. Public scenes that are also bundled appear once, as
/// bundled. Without a readable manifest, every .obj under `scenes` is listed instead.
SceneCatalog scene_catalog(const std::filesystem::path& assets,
                           const std::filesystem::path& scenes);

/// The same with the scenes folder the tests use: $EDACRT_SCENES, else ../shared/scenes
/// beside the repository that holds `assets`.
SceneCatalog scene_catalog(const std::filesystem::path& assets);

}  // namespace edacrt::app
