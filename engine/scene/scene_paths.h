#pragma once
// Where the large public scenes live: outside the repository, so that it stays small.
#include <filesystem>

namespace edacrt {

/// $EDACRT_SCENES when set, else ../shared/scenes beside the repository at `source_dir`.
std::filesystem::path default_scenes_dir(const std::filesystem::path& source_dir);

}  // namespace edacrt
