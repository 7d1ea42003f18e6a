// The viewer's own files: a script or scene manifest that is a FIFO or a directory is refused
// without blocking.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "scene_catalog.h"
#include "script.h"
#include "temp_dir.h"
#include "util/error.h"

namespace edacrt::app {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

TEST(ViewerFiles, AScriptMustBeARegularFile) {
    const TempDir dir;
    const fs::path fifo = dir.path() / "script.txt";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const fs::path& path : {fifo, dir.path(), fs::path("/dev/zero")}) {
        try {
            load_script(path.string());
            ADD_FAILURE() << path;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos)
                << e.what();
        }
    }
}

TEST(ViewerFiles, AManifestThatIsAFifoFallsBackToTheFolder) {
    const TempDir dir;
    fs::create_directories(dir.path() / "assets");
    fs::create_directories(dir.path() / "scenes/b");
    std::ofstream(dir.path() / "scenes/b/b.obj") << "v 0 0 0\n";
    ASSERT_EQ(::mkfifo((dir.path() / "assets/scenes.json").c_str(), 0600), 0);
    const SceneCatalog catalog = scene_catalog(dir.path() / "assets", dir.path() / "scenes");
    EXPECT_TRUE(std::any_of(catalog.entries.begin(), catalog.entries.end(), [&](const auto& e) {
        return e.path == (dir.path() / "scenes/b/b.obj").string();
    }));
}

}  // namespace
}  // namespace edacrt::app
