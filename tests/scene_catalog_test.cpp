// The viewer's scene list: bundled scenes, the manifest's public scenes present or not (and the
// hint to fetch the rest), built-ins; a missing or malformed manifest falls back to the folder.
#include "scene_catalog.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>

#include "scene/animation.h"

namespace edacrt::app {
namespace {

namespace fs = std::filesystem;

class SceneCatalogTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("edacrt_scene_catalog_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        touch(assets() / "a" / "a.obj");
        touch(scenes() / "b" / "b.obj");
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path assets() const { return dir_ / "repo" / "assets"; }
    fs::path scenes() const { return dir_ / "scenes"; }
    static void touch(const fs::path& path, const std::string& text = "v 0 0 0\n") {
        fs::create_directories(path.parent_path());
        std::ofstream(path) << text;
    }
    void write_manifest(const std::string& scenes_json) const {
        touch(assets() / "scenes.json", R"({"downloads": {}, "scenes": )" + scenes_json + "}");
    }

    fs::path dir_;
};

constexpr const char* kThree = R"([
    {"folder": "a", "scene": "a.obj", "triangles": 1},
    {"folder": "b", "scene": "b.obj", "triangles": 69451},
    {"folder": "c", "scene": "c.obj", "triangles": 3}])";

TEST_F(SceneCatalogTest, BundledThenPublicPresentOrNotThenBuiltins) {
    write_manifest(kThree);
    const SceneCatalog catalog = scene_catalog(assets(), scenes());
    ASSERT_EQ(catalog.entries.size(), 6u);
    EXPECT_EQ(catalog.entries[0].path, (assets() / "a" / "a.obj").string());  // bundled, once
    EXPECT_TRUE(catalog.entries[0].present);
    EXPECT_EQ(catalog.entries[1].label, "b (69,451 triangles)");
    EXPECT_EQ(catalog.entries[1].path, (scenes() / "b" / "b.obj").string());
    EXPECT_TRUE(catalog.entries[1].present);
    EXPECT_EQ(catalog.entries[2].label, "c (not downloaded)");
    EXPECT_EQ(catalog.entries[2].path, (scenes() / "c" / "c.obj").string());
    EXPECT_FALSE(catalog.entries[2].present);
    EXPECT_EQ(catalog.entries[3].path, "builtin:cornell");
    EXPECT_EQ(catalog.missing, 1);
    EXPECT_NE(catalog.hint.find("1 more scene: run scripts/get-scenes"), std::string::npos)
        << catalog.hint;
    // The folder is the hint's tooltip: the hint's length does not depend on the checkout's.
    EXPECT_EQ(catalog.hint.find(dir_.string()), std::string::npos) << catalog.hint;
    EXPECT_EQ(catalog.scenes_folder, scenes().string());
}

TEST_F(SceneCatalogTest, NoHintWhenEverythingIsThere) {
    write_manifest(kThree);
    touch(scenes() / "c" / "c.obj");
    const SceneCatalog catalog = scene_catalog(assets(), scenes());
    EXPECT_EQ(catalog.missing, 0);
    EXPECT_TRUE(catalog.hint.empty());
    EXPECT_TRUE(std::all_of(catalog.entries.begin(), catalog.entries.end(),
                            [](const CatalogEntry& e) { return e.present; }));
}

TEST_F(SceneCatalogTest, WithoutAUsableManifestTheFolderIsListed) {
    for (const std::string manifest : {"", "{not json", R"({"scenes": [{"folder": 3}]})"}) {
        if (!manifest.empty()) touch(assets() / "scenes.json", manifest);
        const SceneCatalog catalog = scene_catalog(assets(), scenes());
        ASSERT_EQ(catalog.entries.size(), 5u) << manifest;
        EXPECT_EQ(catalog.entries[1].path, (scenes() / "b" / "b.obj").string());
        EXPECT_TRUE(catalog.hint.empty());
    }
}

TEST_F(SceneCatalogTest, NoScenesFolderMeansEveryPublicSceneIsMissing) {
    write_manifest(kThree);
    const SceneCatalog catalog = scene_catalog(assets(), dir_ / "nowhere");
    EXPECT_EQ(catalog.missing, 2);
    EXPECT_NE(catalog.hint.find("2 more scenes"), std::string::npos);
}

// The repository's own manifest: the three bundled scenes once, the seven others as present
// or not in the scenes folder the tests use.
TEST(SceneCatalog, TheRepositorysManifest) {
    const SceneCatalog catalog = scene_catalog(fs::path(EDACRT_SOURCE_DIR) / "assets");
    int bundled = 0, animations = 0, public_scenes = 0, missing = 0;
    for (const CatalogEntry& e : catalog.entries) {
        if (e.path.starts_with("builtin:")) continue;
        if (e.path.ends_with(".anim.json")) {  // the bundled animation, loadable as a scene
            ++animations;
            EXPECT_NE(e.label.find("(animated)"), std::string::npos) << e.label;
            EXPECT_TRUE(load_animated_scene("", e.path).animation) << e.path;
            continue;
        }
        if (e.path.find("/assets/") != std::string::npos) {
            ++bundled;
            continue;
        }
        ++public_scenes;
        EXPECT_EQ(e.present, fs::is_regular_file(e.path)) << e.path;
        missing += !e.present;
    }
    EXPECT_EQ(bundled, 3);
    EXPECT_EQ(animations, 1);
    EXPECT_EQ(public_scenes, 7);
    EXPECT_EQ(catalog.missing, missing);
}

}  // namespace
}  // namespace edacrt::app
