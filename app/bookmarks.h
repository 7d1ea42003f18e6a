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

    /// Reads the file; a missing file is no bookmarks. Keeps every entry that can be read and
    /// returns one message per problem (a bad entry skipped, a file that cannot be read or
    /// parsed). A file with problems is damaged(): the next save() moves it to a backup first.
    /// A path that exists but cannot be read at all (a loop of symbolic links) is never saved.
    std::vector<std::string> load(const std::string& path);
    /// Writes the file whole or not at all (util/output_file.h), creating its folder. A damaged
    /// file is first renamed to a backup beside it (`.bak`, else `.bak.1`, ...), whose path is
    /// returned (else empty). Throws InputError when the backup or the write fails; the file
    /// on disk is then unchanged and no backup left.
    std::string save(const std::string& path);

    /// True when the file loaded had problems and has not been backed up yet.
    bool damaged() const { return damaged_; }
    /// True when the file exists but could not be read at all: save() refuses to replace it.
    bool unreadable() const { return unreadable_; }

    /// The bookmarks of a scene (keyed by its absolute path, or the built-in spec).
    const std::vector<Bookmark>& of(const std::string& scene) const;
    /// Adds or replaces (by name) a bookmark; removes one by name.
    void put(const std::string& scene, Bookmark bookmark);
    void remove(const std::string& scene, const std::string& name);

    /// The key a scene spec is filed under.
    static std::string scene_key(const std::string& spec);

  private:
    std::map<std::string, std::vector<Bookmark>> by_scene_;
    bool damaged_ = false;
    bool unreadable_ = false;
};

}  // namespace edacrt::app
