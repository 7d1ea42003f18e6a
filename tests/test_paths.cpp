#include "test_paths.h"

#include <cstdlib>

namespace edacrt::test {

std::filesystem::path source_dir() { return EDACRT_SOURCE_DIR; }

std::filesystem::path scenes_dir() {
    if (const char* env = std::getenv("EDACRT_SCENES"); env && *env) return env;
    return source_dir().parent_path() / "shared" / "scenes";
}

std::filesystem::path cli_path() { return EDACRT_CLI; }

}  // namespace edacrt::test
