// Large-scene tests skip without the scenes directory, and fail in CI when it is there and a
// listed scene is not.
#include "test_paths.h"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace edacrt {
namespace {

/// Sets (or with nullptr unsets) an environment variable for the lifetime of the object.
class EnvOverride {
  public:
    EnvOverride(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value)
            setenv(name, value, 1);
        else
            unsetenv(name);
    }
    ~EnvOverride() {
        if (old_)
            setenv(name_, old_->c_str(), 1);
        else
            unsetenv(name_);
    }

  private:
    const char* name_;
    std::optional<std::string> old_;
};

class MissingScene : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("edacrt_scenes_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_ / "present");
        std::ofstream(dir_ / "present/scene.obj") << "v 0 0 0\n";
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path dir_;
};

TEST_F(MissingScene, APresentSceneIsNotMissing) {
    const EnvOverride scenes("EDACRT_SCENES", dir_.c_str()), ci("CI", "true");
    EXPECT_EQ(test::missing_scene("present/scene.obj"), "");
}

TEST_F(MissingScene, SkipsOutsideCi) {
    const EnvOverride scenes("EDACRT_SCENES", dir_.c_str()), ci("CI", nullptr);
    EXPECT_NE(test::missing_scene("gone/scene.obj").find("is missing or unreadable"),
              std::string::npos);
}

TEST_F(MissingScene, FailsInCiWhenTheScenesDirectoryIsThere) {
    const EnvOverride scenes("EDACRT_SCENES", dir_.c_str()), ci("CI", "true");
    EXPECT_NONFATAL_FAILURE(test::missing_scene("gone/scene.obj"), "gone/scene.obj is missing");
    EXPECT_NONFATAL_FAILURE(test::missing_scene("present"), "present is missing or unreadable");
}

TEST_F(MissingScene, SkipsInCiWithoutAScenesDirectory) {
    const EnvOverride scenes("EDACRT_SCENES", (dir_ / "none").c_str()), ci("CI", "true");
    EXPECT_NE(test::missing_scene("gone/scene.obj").find("not found"), std::string::npos);
}

}  // namespace
}  // namespace edacrt
