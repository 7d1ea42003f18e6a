#include "bookmarks.h"

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "util/error.h"
#include "util/input_file.h"
#include "util/json_limits.h"
#include "util/output_file.h"

namespace edacrt::app {
namespace {

using nlohmann::json;

json vec3(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

glm::vec3 vec3(const json& j) {
    if (!j.is_array() || j.size() != 3)
        throw InputError("expected [x, y, z], got " + json_excerpt(j));
    return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()};
}

// Far above any real file (a bookmark is about 200 bytes).
constexpr std::uint64_t kMaxBookmarksBytes = 16u << 20;

/// `text` without the commas that directly precede a closing bracket (outside strings).
std::string without_trailing_commas(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    JsonStrings strings;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (strings.outside(c) && c == ',') {
            const std::size_t next = text.find_first_not_of(" \t\r\n", i + 1);
            if (next != std::string_view::npos && (text[next] == ']' || text[next] == '}'))
                continue;
        }
        out += c;
    }
    return out;
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

std::vector<std::string> Bookmarks::load(const std::string& path) {
    by_scene_.clear();
    damaged_ = false;
    std::vector<std::string> problems;
    const auto problem = [&](const std::string& what) {
        problems.push_back(path + ": " + what);
        damaged_ = true;
    };
    std::error_code error;
    if (!std::filesystem::exists(path, error)) return problems;
    json root;
    try {
        const std::string text = read_text_file(path, "bookmarks file", kMaxBookmarksBytes);
        check_json_depth(text, path);
        root = json::parse(text, nullptr, false);
        if (root.is_discarded()) {
            // A trailing comma is the commonest slip of a hand edit: read past it.
            root = json::parse(without_trailing_commas(text), nullptr, false);
            if (!root.is_discarded()) problem("trailing commas ignored (JSON allows none)");
        }
        if (root.is_discarded()) parse_json(text, path);  // throws with the parser's message
    } catch (const InputError& e) {
        problems.push_back(e.what());
        damaged_ = true;
        return problems;
    }
    if (!root.is_object() || !root.contains("scenes") || !root["scenes"].is_object()) {
        problem("not a bookmarks file (expected {\"scenes\": {...}})");
        return problems;
    }
    for (const auto& [scene, list] : root["scenes"].items()) {
        const std::string where = "scenes[" + json_excerpt(scene) + "]";
        if (!list.is_array()) {
            problem(where + ": expected a list of bookmarks, skipped");
            continue;
        }
        for (std::size_t i = 0; i < list.size(); ++i) try {
                const json& b = list[i];
                Bookmark bookmark;
                bookmark.name = b.at("name").get<std::string>();
                bookmark.camera = {vec3(b.at("eye")), vec3(b.at("look_at")), vec3(b.at("up")),
                                   b.at("fov").get<float>()};
                validate(bookmark.camera);
                by_scene_[scene].push_back(std::move(bookmark));
            } catch (const std::exception& e) {
                problem(where + "[" + std::to_string(i) + "]: skipped: " + shorten(e.what(), 200));
            }
    }
    return problems;
}

std::string Bookmarks::save(const std::string& path) {
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
    std::string backup;
    if (damaged_ && std::filesystem::exists(file, error)) {
        // What could not be read must not be lost: a copy first, never over an older one.
        backup = path + ".bak";
        for (int n = 1; std::filesystem::exists(backup, error); ++n)
            backup = path + ".bak." + std::to_string(n);
        if (!std::filesystem::copy_file(file, backup, error))
            throw InputError(path +
                             ": bookmarks not saved: cannot keep a copy of the damaged "
                             "file as " +
                             backup + " (" + error.message() + ")");
    }
    damaged_ = false;
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), error);
    write_file(file, json{{"version", 1}, {"scenes", scenes}}.dump(2) + "\n", "bookmarks");
    return backup;
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
