#include "scene/scene_paths.h"

#include <cstdlib>

namespace edacrt {

std::filesystem::path default_scenes_dir(const std::filesystem::path& source_dir) {
    if (const char* env = std::getenv("EDACRT_SCENES"); env && *env) return env;
    return source_dir.parent_path() / "shared" / "scenes";
}

}  // namespace edacrt
