#pragma once
// Where tests find their data. Large scenes live outside the repository; tests that need them
// call GTEST_SKIP() with a clear message when they are absent.
#include <filesystem>

namespace edacrt::test {

/// The repository root (assets/, tests/data/).
std::filesystem::path source_dir();

/// The large public scenes: $EDACRT_SCENES, else ../shared/scenes beside the repository.
std::filesystem::path scenes_dir();

/// The edacrt command-line tool built with this test binary.
std::filesystem::path cli_path();

}  // namespace edacrt::test
