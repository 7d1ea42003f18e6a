#include "bookmarks.h"

#include <fcntl.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

/// Renames `from` to `to` unless `to` exists (then fails with EEXIST); 0 or -1 as rename().
int rename_no_replace(const std::filesystem::path& from, const std::filesystem::path& to) {
    if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return 0;
    if (errno != EINVAL && errno != ENOSYS) return -1;
    // A file system without RENAME_NOREPLACE: look first (racing only another writer).
    std::error_code error;
    if (std::filesystem::exists(std::filesystem::symlink_status(to, error))) {
        errno = EEXIST;
        return -1;
    }
    return std::rename(from.c_str(), to.c_str());
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
    unreadable_ = false;
    std::vector<std::string> problems;
    const auto problem = [&](const std::string& what) {
        problems.push_back(path + ": " + what);
        damaged_ = true;
    };
    std::error_code error;
    if (!std::filesystem::exists(path, error)) {
        // Missing is no bookmarks; a loop of symbolic links (or a folder that cannot be
        // searched) is a file that exists but cannot be read, and must not be replaced.
        if (error && error != std::errc::no_such_file_or_directory &&
            error != std::errc::not_a_directory) {
            problem("cannot read the bookmarks file (" + error.message() + ")");
            unreadable_ = true;
        }
        return problems;
    }
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
    if (unreadable_)
        throw InputError(path +
                         ": the file could not be read when loaded (see the warning then); "
                         "not replaced");
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
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::path file(path);
    fs::path damaged_file;  // the damaged content, moved to `backup` while the new one is written
    std::string backup;
    if (damaged_ && fs::exists(file, error)) {
        if (!fs::is_regular_file(file, error))
            throw InputError(path + ": not a regular file; not replaced by bookmarks");
        // What could not be read must not be lost: renamed aside (atomic, and no copy to run
        // out of space or time on, whatever its size), never over an older backup. A symbolic
        // link stays; the file it names is moved.
        damaged_file =
            fs::is_symlink(fs::symlink_status(file, error)) ? fs::canonical(file, error) : file;
        if (error)
            throw InputError(path + ": cannot resolve the link to the damaged file (" +
                             error.message() + ")");
        int result = -1;
        for (int n = 0; n < 1000 && result != 0; ++n) {
            backup = damaged_file.string() + ".bak" + (n ? "." + std::to_string(n) : "");
            result = rename_no_replace(damaged_file, backup);
            if (result != 0 && errno != EEXIST) break;
        }
        if (result != 0)
            throw InputError(path +
                             ": bookmarks not saved: cannot move the damaged file aside "
                             "to " +
                             backup + " (" + std::strerror(errno) + ")");
    }
    if (file.has_parent_path()) fs::create_directories(file.parent_path(), error);
    try {
        // Where the damaged file was: a link to it now dangles, and would be replaced.
        write_file(damaged_file.empty() ? file : damaged_file,
                   json{{"version", 1}, {"scenes", scenes}}.dump(2) + "\n", "bookmarks");
    } catch (const InputError& e) {
        // The damaged file goes back where it was, so nothing is left beside it.
        if (!backup.empty() && rename_no_replace(backup, damaged_file) != 0)
            throw InputError(std::string(e.what()) + "; the damaged file is kept as " + backup);
        throw;
    }
    damaged_ = false;
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
