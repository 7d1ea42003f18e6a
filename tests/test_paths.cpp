#include "test_paths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string_view>

#include "scene/scene_paths.h"

namespace edacrt::test {

std::filesystem::path source_dir() { return EDACRT_SOURCE_DIR; }

std::filesystem::path scenes_dir() { return default_scenes_dir(source_dir()); }

std::filesystem::path cli_path() { return EDACRT_CLI; }

std::string missing_scene(const std::filesystem::path& relative) {
    const std::filesystem::path dir = scenes_dir(), path = dir / relative;
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec) && std::ifstream(path).good()) return {};
    const bool have_scenes = std::filesystem::is_directory(dir, ec);
    const std::string why =
        path.string() + (have_scenes ? " is missing or unreadable" : " not found") +
        " (large scenes are looked up in $EDACRT_SCENES, else ../shared/scenes beside the "
        "repository; scripts/get-scenes fetches them)";
    const char* ci = std::getenv("CI");
    if (have_scenes && ci && std::string_view(ci) == "true") ADD_FAILURE() << why;
    return why;
}

}  // namespace edacrt::test
