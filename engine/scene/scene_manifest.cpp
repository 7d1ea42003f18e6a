#include "scene/scene_manifest.h"

#include <algorithm>

#include "scene/text_scan.h"
#include "util/error.h"
#include "util/input_file.h"
#include "util/json_limits.h"

namespace edacrt {

const ManifestScene* SceneManifest::find(std::string_view name) const {
    const auto it = std::find_if(scenes.begin(), scenes.end(), [&](const ManifestScene& s) {
        return text_scan::equals_ignoring_case(s.name, name);
    });
    return it == scenes.end() ? nullptr : &*it;
}

const std::vector<std::string>& SceneManifest::list(const std::string& list) const {
    const auto it = lists.find(list);
    if (it == lists.end()) throw InputError("the scene manifest has no list '" + list + "'");
    return it->second;
}

std::string SceneManifest::names() const {
    std::string text;
    for (const ManifestScene& s : scenes) text += (text.empty() ? "" : ", ") + s.name;
    return text;
}

SceneManifest read_scene_manifest(const std::filesystem::path& path) {
    const std::string source = path.string();
    const nlohmann::json json = parse_json(read_text_file(path, "scene manifest"), source);
    const auto fail = [&](const std::string& what) { throw InputError(source + ": " + what); };
    if (!json.is_object() || !json.contains("scenes") || !json["scenes"].is_array())
        fail("no \"scenes\" array");
    const auto text = [&](const nlohmann::json& object, const char* key) -> const std::string* {
        const auto it = object.find(key);
        return it != object.end() && it->is_string() ? it->get_ptr<const std::string*>() : nullptr;
    };
    SceneManifest manifest;
    for (const nlohmann::json& entry : json["scenes"]) {
        const std::string* folder = entry.is_object() ? text(entry, "folder") : nullptr;
        const std::string* file = folder ? text(entry, "scene") : nullptr;
        if (!file)
            fail("a scene without a string \"folder\" and \"scene\": " + json_excerpt(entry));
        ManifestScene scene{*folder, *folder, *file};
        if (entry.contains("name")) {
            const std::string* name = text(entry, "name");
            if (!name || name->empty()) fail(*folder + ": \"name\" must be a non-empty string");
            scene.name = *name;
        }
        if (const auto it = entry.find("triangles"); it != entry.end() && it->is_number_integer())
            scene.triangles = it->get<long long>();
        if (const auto it = entry.find("interior"); it != entry.end()) {
            if (!it->is_boolean()) fail(scene.name + ": \"interior\" must be true or false");
            scene.interior = it->get<bool>();
        }
        if (manifest.find(scene.name)) fail("two scenes are called " + scene.name);
        manifest.scenes.push_back(std::move(scene));
    }
    if (const auto lists = json.find("lists"); lists != json.end()) {
        if (!lists->is_object()) fail("\"lists\" must be an object");
        for (const auto& [name, list] : lists->items()) {
            const auto members = list.is_object() ? list.find("scenes") : list.end();
            if (members == list.end() || !members->is_array())
                fail("list " + name + " has no \"scenes\" array");
            std::vector<std::string>& names = manifest.lists[name];
            for (const nlohmann::json& member : *members) {
                const ManifestScene* scene =
                    member.is_string() ? manifest.find(member.get<std::string>()) : nullptr;
                if (!scene || scene->name != member.get<std::string>())
                    fail("list " + name + ": " + json_excerpt(member) + " is not a scene's name");
                names.push_back(member.get<std::string>());
            }
        }
    }
    return manifest;
}

std::filesystem::path scene_manifest_path(const std::filesystem::path& source_dir) {
    return source_dir / "assets" / "scenes.json";
}

bool is_bundled(const ManifestScene& scene, const std::filesystem::path& assets) {
    std::error_code error;
    return std::filesystem::is_regular_file(assets / scene.folder / scene.file, error);
}

std::filesystem::path scene_file(const ManifestScene& scene, const std::filesystem::path& assets,
                                 const std::filesystem::path& scenes_dir) {
    return (is_bundled(scene, assets) ? assets : scenes_dir) / scene.folder / scene.file;
}

}  // namespace edacrt
