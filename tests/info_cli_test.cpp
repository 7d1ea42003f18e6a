// edacrt info against counts taken from the files themselves: triangles by fan triangulation of
// the `f` lines, vertices from the `v` lines, materials from `newmtl`, emitters from `Ke`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.h"
#include "temp_dir.h"
#include "test_paths.h"

namespace edacrt {
namespace {

/// What a plain reading of an OBJ (and its MTL) says.
struct Counted {
    std::size_t triangles = 0, vertices = 0, materials = 0, emissive_triangles = 0;
    std::map<std::string, std::size_t> per_material;  // triangles after each usemtl
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
};

Counted count_obj(const std::filesystem::path& obj) {
    Counted c;
    std::map<std::string, bool> emissive;
    std::ifstream in(obj);
    std::string line, current = "default";
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "v") {
            ++c.vertices;
            for (int k = 0; k < 3; ++k) {
                double x;
                words >> x;
                c.lo[k] = std::min(c.lo[k], x);
                c.hi[k] = std::max(c.hi[k], x);
            }
        } else if (keyword == "f") {
            std::size_t corners = 0;
            for (std::string corner; words >> corner;) ++corners;
            c.triangles += corners - 2;
            c.per_material[current] += corners - 2;
            if (emissive[current]) c.emissive_triangles += corners - 2;
        } else if (keyword == "usemtl") {
            words >> current;
        } else if (keyword == "mtllib") {
            std::string name;
            words >> name;
            std::ifstream mtl(obj.parent_path() / name);
            std::string material;
            for (std::string m; std::getline(mtl, m);) {
                std::istringstream mw(m);
                std::string key;
                mw >> key;
                if (key == "newmtl") {
                    mw >> material;
                    ++c.materials;
                }
                double r = 0, g = 0, b = 0;
                if (key == "Ke" && (mw >> r >> g >> b) && r + g + b > 0) emissive[material] = true;
            }
        }
    }
    if (c.materials == 0) c.materials = 1;  // the default material
    return c;
}

nlohmann::json info_json(const std::string& scene) {
    // stdout alone: the JSON must parse with nothing else in it.
    const auto result = test::run_command("('" + test::cli_path().string() + "' info '" + scene +
                                          "' --json 2>/dev/null)");
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return nlohmann::json::parse(result.output);
}

TEST(InfoCli, BundledScenesMatchTheirFiles) {
    for (const char* relative : {"assets/cornell-box/CornellBox-Original.obj",
                                 "assets/spot/spot.obj", "assets/teapot/teapot.obj"}) {
        const std::filesystem::path obj = test::source_dir() / relative;
        const Counted c = count_obj(obj);
        const nlohmann::json info = info_json(obj.string());
        EXPECT_EQ(info["triangles"].get<std::size_t>(), c.triangles) << relative;
        EXPECT_EQ(info["degenerate_triangles"].get<std::size_t>(), 0u) << relative;
        EXPECT_EQ(info["vertices"].get<std::size_t>(), c.vertices) << relative;
        EXPECT_EQ(info["materials"].size(), c.materials) << relative;
        EXPECT_EQ(info["emitters"]["triangles"].get<std::size_t>(), c.emissive_triangles)
            << relative;
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(info["bounds"]["min"][k].get<double>(), c.lo[k], 1e-6) << relative;
            EXPECT_NEAR(info["bounds"]["max"][k].get<double>(), c.hi[k], 1e-6) << relative;
        }
        if (c.per_material.size() > 1) {
            for (const auto& m : info["materials"]) {
                EXPECT_EQ(m["triangles"].get<std::size_t>(),
                          c.per_material.at(m["name"].get<std::string>()))
                    << m["name"];
            }
        }
        EXPECT_TRUE(info["warnings"].empty()) << info["warnings"];
        for (const char* method : {"edacrt", "dacrt", "bvh", "naive"})
            EXPECT_GT(info["memory"]["tracer_scene_bytes"][method].get<std::uint64_t>(), 0u);
    }
}

TEST(InfoCli, CornellBoxFactsByHand) {
    // Numbers from the file (36 triangles from 18 quads, 72 vertices, 8 materials, one
    // quad light with Ke 17 12 4) and render's defaults (512x512).
    const nlohmann::json info =
        info_json((test::source_dir() / "assets/cornell-box/CornellBox-Original.obj").string());
    EXPECT_EQ(info["triangles"], 36);
    EXPECT_EQ(info["vertices"], 72);
    EXPECT_EQ(info["materials"].size(), 8u);
    EXPECT_EQ(info["emitters"]["triangles"], 2);
    for (const auto& m : info["materials"]) {
        if (m["name"] == "light") {
            EXPECT_NE(m["model"].get<std::string>().find("emits Ke 17 12 4"), std::string::npos);
        }
    }
    EXPECT_EQ(info["camera"]["from"], "framing the bounds from +z");
    EXPECT_EQ(info["memory"]["width"], 512);
    EXPECT_GT(info["memory"]["renderer_bytes"].get<std::uint64_t>(), 512u * 512u * 24u);
}

TEST(InfoCli, DegenerateFacesMissingTexturesAndUnmodelledStatementsAreReported) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("edacrt_info_cli_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "s.mtl") << "newmtl glass\nillum 7\nNi 1.33\nmap_Kd -bm 1 gone.png\n"
                                    "d 0.5\n";
    std::ofstream(dir / "s.obj") << "mtllib s.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                                    "usemtl glass\nf 1 2 3\nf 1 2 4\nf 1 1 3\nf 1 2 3 4\n";
    const nlohmann::json info = info_json((dir / "s.obj").string());
    std::filesystem::remove_all(dir);
    EXPECT_EQ(info["triangles"], 5);             // 1 + 1 + 1 + 2 (the quad's fan)
    EXPECT_EQ(info["degenerate_triangles"], 2);  // 1 2 4 collinear, 1 1 3 a repeated corner
    ASSERT_EQ(info["materials"].size(), 1u);
    EXPECT_EQ(info["materials"][0]["model"], "smooth dielectric Ni 1.33, Tf 1 1 1 (illum 7)");
    EXPECT_EQ(info["materials"][0]["textures"][0]["file"], "gone.png");
    std::string warnings;
    for (const auto& w : info["warnings"]) warnings += w.get<std::string>() + "\n";
    for (const char* expected :
         {"gone.png: cannot read the texture (no such file); Kd alone is used",
          "MTL feature 'd' is not modelled", "2 degenerate triangles"})
        EXPECT_NE(warnings.find(expected), std::string::npos) << expected << "\n" << warnings;

    const auto text = test::run_cli("info builtin:cornell --width 64 --height 32");
    EXPECT_EQ(text.exit_code, 0) << text.output;
    EXPECT_NE(text.output.find("64x32 path render at 16 spp"), std::string::npos) << text.output;
    EXPECT_NE(test::run_cli("info /no/such.obj").exit_code, 0);
    EXPECT_NE(test::run_cli("info builtin:cornell --integrator magic").exit_code, 0);
}

// Names from files are bytes: a Latin-1 name is not UTF-8, which JSON needs. The bytes become
// U+FFFD in the JSON (the text form escapes them) instead of an internal error.
TEST(InfoCli, ALatin1MaterialNameIsReplacedInJson) {
    const test::TempDir dir;
    dir.write("s.mtl", "newmtl caf\xE9\nKd 1 0 0\n");
    const auto obj = dir.write("s.obj",
                               "mtllib s.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                               "usemtl caf\xE9\nf 1 2 3\n");
    const auto result = test::run_cli("info --json " + obj.string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("\"name\": \"caf\xEF\xBF\xBD\""), std::string::npos)
        << result.output;
}

// Names from files reach the terminal escaped: an ESC in a material or texture name cannot
// recolour or clear it. So do errors quoting a path.
TEST(InfoCli, NamesFromFilesArePrintedEscaped) {
    const test::TempDir dir;
    dir.write("s.mtl", "newmtl \x1B[31mred\nmap_Kd \x1B]0;title\x07.png\n");
    const auto obj = dir.write("s.obj",
                               "mtllib s.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                               "usemtl \x1B[31mred\nf 1 2 3\n");
    const auto result = test::run_cli("info " + obj.string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(result.output.find('\x1B'), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("    \\x1B[31mred: 1 triangles"), std::string::npos)
        << result.output;
    EXPECT_NE(result.output.find("map_Kd \\x1B]0;title\\x07.png (not rendered)"), std::string::npos)
        << result.output;
    const auto error = test::run_cli("info '" + (dir.path() / "\x1B[2J.obj").string() + "'");
    EXPECT_EQ(error.exit_code, 1) << error.output;
    EXPECT_EQ(error.output.find('\x1B'), std::string::npos) << error.output;
    EXPECT_NE(error.output.find("\\x1B[2J.obj: cannot read OBJ file"), std::string::npos)
        << error.output;
}

TEST(InfoCli, LargeScenesMatchTheirPublishedCounts) {
    // The scenes README's table: triangles by fan triangulation, vertices, degenerate faces.
    const struct {
        const char* file;
        std::size_t triangles, vertices, materials;
    } scenes[] = {{"bunny/stanford-bunny.obj", 69451, 35947, 1},
                  {"sponza/sponza.obj", 66445, 66350, 19}};
    for (const auto& s : scenes) {
        if (const std::string why = test::missing_scene(s.file); !why.empty()) GTEST_SKIP() << why;
        const nlohmann::json info = info_json((test::scenes_dir() / s.file).string());
        EXPECT_EQ(info["triangles"].get<std::size_t>(), s.triangles) << s.file;
        EXPECT_EQ(info["vertices"].get<std::size_t>(), s.vertices) << s.file;
        EXPECT_EQ(info["materials"].size(), s.materials) << s.file;
    }
}

// A material naming thousands of missing textures once printed a warning and a line for each
// (40,000 lines): both stop after ten, with the count of the rest, in the text and the JSON.
TEST(InfoCli, ManyMissingTexturesAreCappedWithACount) {
    const test::TempDir dir;
    std::string mtl = "newmtl a\n";
    for (int i = 0; i < 50; ++i) mtl += "map_Kd missing" + std::to_string(i) + ".png\n";
    dir.write("many.mtl", mtl);
    const auto obj = dir.write("many.obj",
                               "mtllib many.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                               "usemtl a\nf 1 2 3\n");
    const auto text = test::run_cli("info " + obj.string());
    ASSERT_EQ(text.exit_code, 0) << text.output;
    const auto count = [&](const std::string& what) {
        std::size_t n = 0;
        for (std::size_t at = text.output.find(what); at != std::string::npos;
             at = text.output.find(what, at + 1))
            ++n;
        return n;
    };
    EXPECT_EQ(count(".png is missing"), 10u) << text.output;
    EXPECT_EQ(count(".png (not rendered)"), 10u) << text.output;
    // The last map_Kd is the one decoded: the loader reports it, the summary the others.
    EXPECT_NE(text.output.find("missing49.png: cannot read the texture (no such file)"),
              std::string::npos)
        << text.output;
    EXPECT_NE(text.output.find(obj.string() + ": ... and 39 more missing textures"),
              std::string::npos)
        << text.output;
    EXPECT_NE(text.output.find("... and 40 more textures\n"), std::string::npos) << text.output;

    const auto json = test::run_cli("info --json " + obj.string() + " 2>/dev/null");
    ASSERT_EQ(json.exit_code, 0) << json.output;
    const auto info = nlohmann::json::parse(json.output);
    std::size_t missing = 0;
    for (const auto& w : info["warnings"])
        missing += w.get<std::string>().find(".png is missing") != std::string::npos;
    EXPECT_EQ(missing, 10u) << info["warnings"].dump(1);
    EXPECT_EQ(info["warnings"].back(), obj.string() + ": ... and 39 more missing textures");
}

// info traces nothing, so a scene beyond Embree's range is described (the limit a note), and a
// scene whose default camera overflows names itself and the flags that replace that camera.
TEST(InfoCli, ASceneEmbreeCannotTraceIsDescribedAndAnOverflowingCameraNamed) {
    const test::TempDir dir;
    const auto far = dir.write("far.obj", "v 1e30 0 0\nv 1e30 1e-30 0\nv 1e30 0 1e-30\nf 1 2 3\n");
    const auto text = test::run_cli("info " + far.string());
    ASSERT_EQ(text.exit_code, 0) << text.output;
    EXPECT_NE(text.output.find("triangles    1 "), std::string::npos) << text.output;
#ifdef EDACRT_HAS_EMBREE
    EXPECT_NE(text.output.find("note         embree cannot trace it: "), std::string::npos)
        << text.output;
    const auto json = test::run_cli("info --json " + far.string() + " 2>/dev/null");
    ASSERT_EQ(json.exit_code, 0) << json.output;
    const auto info = nlohmann::json::parse(json.output);
    EXPECT_TRUE(info["memory"]["tracer_scene_bytes"]["embree"].is_null());
    EXPECT_GT(info["memory"]["tracer_scene_bytes"]["edacrt"].get<std::uint64_t>(), 0u);
    EXPECT_NE(info["memory"]["methods_that_cannot_trace"]["embree"].get<std::string>().find(
                  "coordinates reach 1e+30"),
              std::string::npos)
        << info.dump(1);
#endif

    const auto huge = dir.write("huge.obj", "v 1e38 0 0\nv -1e38 0 0\nv 0 1e38 0\nf 1 2 3\n");
    const auto refused = test::run_cli("info " + huge.string());
    EXPECT_EQ(refused.exit_code, 1) << refused.output;
    EXPECT_NE(refused.output.find(huge.string() +
                                  ": the default camera from its bounds is not finite "
                                  "(coordinates near the float limit); give --eye and --look-at"),
              std::string::npos)
        << refused.output;
}

}  // namespace
}  // namespace edacrt
