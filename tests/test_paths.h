#pragma once
// Where tests find their data. Large scenes live outside the repository; tests that need them
// skip when the scenes directory is absent, but fail in CI when it is there and a scene is not.
#include <filesystem>
#include <string>

namespace edacrt::test {

/// The repository root (assets/, tests/data/).
std::filesystem::path source_dir();

/// The large public scenes: $EDACRT_SCENES, else ../shared/scenes beside the repository.
std::filesystem::path scenes_dir();

/// Empty when the large scene `relative` (to scenes_dir()) is a readable file. Otherwise why
/// not, for GTEST_SKIP(); in CI ($CI=true) with the scenes directory present, the test has also
/// failed, so a listed scene that went missing cannot pass as a skip.
std::string missing_scene(const std::filesystem::path& relative);

/// The edacrt command-line tool built with this test binary.
std::filesystem::path cli_path();

}  // namespace edacrt::test
