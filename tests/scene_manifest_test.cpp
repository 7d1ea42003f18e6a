// assets/scenes.json, the one scene list: the repository's own (every list the benchmarks read
// names known scenes, the bundled ones are found in assets/), and the errors a bad one gives.
#include "scene/scene_manifest.h"

#include <gtest/gtest.h>

#include "temp_dir.h"
#include "test_paths.h"
#include "util/error.h"

namespace edacrt {
namespace {

TEST(SceneManifest, TheRepositorysListsNameItsScenes) {
    const std::filesystem::path assets = test::source_dir() / "assets";
    const SceneManifest manifest = read_scene_manifest(scene_manifest_path(test::source_dir()));
    for (const char* list :
         {"bench", "bench_dynamic", "paper", "report", "deviations", "trace_benchmark"}) {
        EXPECT_FALSE(manifest.list(list).empty()) << list;
        for (const std::string& name : manifest.list(list)) EXPECT_TRUE(manifest.find(name));
    }
    int bundled = 0;
    for (const ManifestScene& scene : manifest.scenes) bundled += is_bundled(scene, assets);
    EXPECT_EQ(bundled, 3);
    ASSERT_TRUE(manifest.find("Cornell"));  // any case; "name" over the folder cornell-box
    EXPECT_EQ(scene_file(*manifest.find("cornell"), assets, "/nowhere"),
              assets / "cornell-box" / "CornellBox-Original.obj");
    EXPECT_EQ(scene_file(*manifest.find("bunny"), assets, "/nowhere"),
              std::filesystem::path("/nowhere/bunny/stanford-bunny.obj"));
    EXPECT_TRUE(manifest.find("sponza")->interior);
    EXPECT_FALSE(manifest.find("bunny")->interior);
    EXPECT_THROW(manifest.list("no-such-list"), InputError);
}

TEST(SceneManifest, ABadManifestIsRefusedWithTheReason) {
    const test::TempDir dir;
    const auto error = [&](const std::string& text) -> std::string {
        try {
            read_scene_manifest(dir.write("scenes.json", text));
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    const std::string a = R"({"folder": "a", "scene": "a.obj"})";
    EXPECT_NE(error("{").find("scenes.json"), std::string::npos);
    EXPECT_NE(error(R"({"scenes": 3})").find("no \"scenes\" array"), std::string::npos);
    EXPECT_NE(error(R"({"scenes": [{"folder": 3}]})").find("\"folder\""), std::string::npos);
    EXPECT_NE(error(R"({"scenes": [)" + a + "," + a + "]}").find("two scenes are called a"),
              std::string::npos);
    EXPECT_NE(error(R"({"scenes": [)" + a + R"(], "lists": {"l": {"scenes": ["b"]}}})")
                  .find("\"b\" is not a scene's name"),
              std::string::npos);
    EXPECT_NE(error(R"({"scenes": [)" + a + R"(], "lists": {"l": {"scenes": ["A"]}}})")
                  .find("\"A\" is not a scene's name"),
              std::string::npos);  // lists spell names exactly, as bench/bench_common.py reads them
    EXPECT_NE(error(R"({"scenes": [)" + a + R"(], "lists": {"l": ["a"]}})")
                  .find("list l has no \"scenes\" array"),
              std::string::npos);
    EXPECT_NE(error(R"({"scenes": [{"folder": "a", "scene": "a.obj", "interior": 1}]})")
                  .find("\"interior\" must be true or false"),
              std::string::npos);
    const SceneManifest ok = read_scene_manifest(dir.write(
        "ok.json", R"({"scenes": [{"folder": "f", "name": "n", "scene": "s.obj", "triangles": 7}],
                       "lists": {"l": {"about": "why", "scenes": ["n"]}}})"));
    ASSERT_EQ(ok.scenes.size(), 1u);
    EXPECT_EQ(ok.scenes[0].name, "n");
    EXPECT_EQ(ok.scenes[0].triangles, 7);
    EXPECT_EQ(ok.list("l"), std::vector<std::string>{"n"});
    EXPECT_EQ(ok.names(), "n");
}

}  // namespace
}  // namespace edacrt
