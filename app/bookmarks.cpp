#include "bookmarks.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "util/error.h"

namespace edacrt::app {
namespace {

using nlohmann::json;

json vec3(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

glm::vec3 vec3(const json& j) {
    if (!j.is_array() || j.size() != 3) throw InputError("expected [x, y, z]");
    return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()};
}

}  // namespace

std::string Bookmarks::default_path() {
    const char* config = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    std::filesystem::path dir;
    if (config && *config)
        dir = config;
    else if (home && *home)
        dir = std::filesystem::path(home) / ".config";
    else
        return {};
    return (dir / "edacrt" / "bookmarks.json").string();
}

std::string Bookmarks::scene_key(const std::string& spec) {
    if (spec.rfind("builtin:", 0) == 0) return spec;
    std::error_code error;
    const auto absolute = std::filesystem::weakly_canonical(spec, error);
    return error ? spec : absolute.string();
}

void Bookmarks::load(const std::string& path) {
    by_scene_.clear();
    std::ifstream in(path);
    if (!in) return;
    try {
        const json root = json::parse(in);
        for (const auto& [scene, list] : root.at("scenes").items())
            for (const json& b : list) {
                Bookmark bookmark;
                bookmark.name = b.at("name").get<std::string>();
                bookmark.camera = {vec3(b.at("eye")), vec3(b.at("look_at")), vec3(b.at("up")),
                                   b.at("fov").get<float>()};
                validate(bookmark.camera);
                by_scene_[scene].push_back(std::move(bookmark));
            }
    } catch (const std::exception& e) {
        by_scene_.clear();
        throw InputError(path + ": not a bookmarks file: " + e.what());
    }
}

void Bookmarks::save(const std::string& path) const {
    json scenes = json::object();
    for (const auto& [scene, list] : by_scene_) {
        json entries = json::array();
        for (const Bookmark& b : list)
            entries.push_back({{"name", b.name},
                               {"eye", vec3(b.camera.eye)},
                               {"look_at", vec3(b.camera.look_at)},
                               {"up", vec3(b.camera.up)},
                               {"fov", b.camera.vfov_degrees}});
        if (!entries.empty()) scenes[scene] = std::move(entries);
    }
    std::error_code error;
    const std::filesystem::path file(path);
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), error);
    std::ofstream out(path);
    out << json{{"version", 1}, {"scenes", scenes}}.dump(2) << "\n";
    if (!out) throw InputError(path + ": cannot write bookmarks");
}

const std::vector<Bookmark>& Bookmarks::of(const std::string& scene) const {
    static const std::vector<Bookmark> none;
    const auto it = by_scene_.find(scene_key(scene));
    return it == by_scene_.end() ? none : it->second;
}

void Bookmarks::put(const std::string& scene, Bookmark bookmark) {
    auto& list = by_scene_[scene_key(scene)];
    for (Bookmark& b : list)
        if (b.name == bookmark.name) {
            b = std::move(bookmark);
            return;
        }
    list.push_back(std::move(bookmark));
}

void Bookmarks::remove(const std::string& scene, const std::string& name) {
    auto& list = by_scene_[scene_key(scene)];
    std::erase_if(list, [&](const Bookmark& b) { return b.name == name; });
}

}  // namespace edacrt::app
