#pragma once
// Camera bookmarks, saved per scene in a small JSON file beside the user's configuration
// ($XDG_CONFIG_HOME/edacrt/bookmarks.json, else ~/.config/edacrt/bookmarks.json).
#include <map>
#include <string>
#include <vector>

#include "scene/camera.h"

namespace edacrt::app {

struct Bookmark {
    std::string name;
    Camera camera;
};

class Bookmarks {
  public:
    /// Where the file lives for this user; empty when neither XDG_CONFIG_HOME nor HOME is set.
    static std::string default_path();

    /// Reads the file; a missing file is no bookmarks. Throws InputError for a malformed one.
    void load(const std::string& path);
    /// Writes the file, creating its folder. Throws InputError when it cannot.
    void save(const std::string& path) const;

    /// The bookmarks of a scene (keyed by its absolute path, or the built-in spec).
    const std::vector<Bookmark>& of(const std::string& scene) const;
    /// Adds or replaces (by name) a bookmark; removes one by name.
    void put(const std::string& scene, Bookmark bookmark);
    void remove(const std::string& scene, const std::string& name);

    /// The key a scene spec is filed under.
    static std::string scene_key(const std::string& spec);

  private:
    std::map<std::string, std::vector<Bookmark>> by_scene_;
};

}  // namespace edacrt::app
