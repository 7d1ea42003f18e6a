// Outputs are replaced whole or not at all: a write that fails (a file-size limit, a full disk)
// leaves the old file as it was, and no two outputs of one edacrt command share a path.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "cli_runner.h"
#include "temp_dir.h"
#include "test_paths.h"
#include "trace/ray_file.h"
#include "util/output_file.h"

namespace edacrt {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

using test::bytes_of;

std::set<std::string> names_in(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        names.insert(entry.path().lexically_relative(dir).string());  // links not followed
    return names;
}

/// Runs edacrt under a file-size limit of one 512-byte block (ulimit -f), SIGXFSZ ignored so
/// that the write fails with EFBIG instead of killing the process.
test::CliResult run_limited(const std::string& args) {
    return test::run_command("trap '' XFSZ; ulimit -f 1; '" + test::cli_path().string() + "' " +
                             args);
}

// Larger than the limit, so a writer that truncated the file in place would lose it.
const std::string kOld = std::string(3000, 'o') + " the old file's bytes\n";

const std::string kRender = "render --scene builtin:cornell --width 96 --height 64 --spp 1 ";

TEST(OutputFile, AnAbandonedWriteLeavesTheOldFileAndNoTemporary) {
    const TempDir dir;
    const fs::path file = dir.write("out.txt", "old");
    {  // written but never closed, as on an error path
        OutputFile out(file, "test file");
        out.write("new content");
        EXPECT_EQ(bytes_of(file), "old");  // not yet replaced
    }
    EXPECT_EQ(bytes_of(file), "old");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), {}), 1);
    write_file(file, "new", "test file");
    EXPECT_EQ(bytes_of(file), "new");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), {}), 1);
}

TEST(OutputFile, SameOutputFileSeesThroughDotsLinksAndHardLinks) {
    const TempDir dir;
    const fs::path a = dir.write("a", "x");
    fs::create_directories(dir.path() / "sub");
    fs::create_hard_link(a, dir.path() / "hard");
    EXPECT_TRUE(same_output_file(a, dir.path() / "sub/../a"));
    EXPECT_TRUE(same_output_file(a, dir.path() / "hard"));
    EXPECT_TRUE(same_output_file(dir.path() / "new", dir.path() / "sub/../new"));
    EXPECT_FALSE(same_output_file(a, dir.path() / "b"));
    EXPECT_FALSE(same_output_file("/dev/null", "/dev/null"));
}

TEST(OutputSafety, AFailedImageWriteKeepsTheOldFile) {
    for (const std::string ext : {"png", "jpg", "hdr", "pfm", "exr"}) {
        const TempDir dir;
        const fs::path out = dir.write("image." + ext, kOld);
        const auto result = run_limited(kRender + "--out " + out.string());
        EXPECT_EQ(result.exit_code, 1) << ext << "\n" << result.output;
        EXPECT_NE(result.output.find("edacrt: error: " + out.string() + ": cannot write"),
                  std::string::npos)
            << result.output;
        EXPECT_NE(result.output.find("File too large"), std::string::npos) << result.output;
        EXPECT_EQ(bytes_of(out), kOld) << ext;
        EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"image." + ext}) << ext;
    }
}

TEST(OutputSafety, AFailedWriteKeepsOldHitsStatsAndFrames) {
    const TempDir dir;
    // 640 bytes of hits: more than one 512-byte block, less than the statistics' 4 KB.
    std::vector<Ray> rays(40, Ray{{0, 0, 5}, {0, 0, -1}, 0.0f, 1e30f});
    write_rays(dir.path() / "rays.bin", rays);
    const fs::path hits = dir.write("hits.bin", kOld);
    const fs::path stats = dir.write("stats.json", kOld);
    const std::string trace = "trace --scene builtin:cornell --rays " +
                              (dir.path() / "rays.bin").string() + " --out " + hits.string();
    auto result = run_limited(trace);
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find(hits.string() + ": cannot write hit file (File too large"),
              std::string::npos)
        << result.output;
    EXPECT_EQ(bytes_of(hits), kOld);
    // The statistics alone fail: the hits are small enough to be written.
    fs::remove(hits);
    result = test::run_command("trap '' XFSZ; ulimit -f 2; '" + test::cli_path().string() + "' " +
                               trace + " --stats " + stats.string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find(stats.string() + ": cannot write statistics (File too large"),
              std::string::npos)
        << result.output;
    EXPECT_EQ(bytes_of(stats), kOld);

    const fs::path frame = dir.write("frame_0001.png", kOld);
    result = run_limited(kRender + "--animate wave:amplitude=0.1 --frames 1:2 --out " +
                         (dir.path() / "frame_%04d.png").string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_EQ(bytes_of(frame), kOld);
    EXPECT_EQ(names_in(dir.path()),
              (std::set<std::string>{"rays.bin", "hits.bin", "stats.json", "frame_0001.png"}));
}

TEST(OutputSafety, ATemporaryThatCannotBeCreatedFailsBeforeTheFileIsTouched) {
    const TempDir dir;
    // The temporary's longer name exceeds the file system's limit of 255 bytes.
    const fs::path out = dir.write(std::string(250, 'n') + ".pfm", kOld);
    const auto result = test::run_cli(kRender + "--out " + out.string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("a temporary file beside it"), std::string::npos) << result.output;
    EXPECT_EQ(bytes_of(out), kOld);
}

TEST(OutputSafety, AReplacedFileKeepsItsModeAndItsLink) {
    const TempDir dir;
    const fs::path real = dir.write("real.pfm", kOld);
    fs::permissions(real, fs::perms::owner_read | fs::perms::owner_write);
    fs::create_symlink(real, dir.path() / "link.pfm");
    const auto result = test::run_cli(kRender + "--out " + (dir.path() / "link.pfm").string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_TRUE(fs::is_symlink(dir.path() / "link.pfm"));
    EXPECT_NE(bytes_of(real), kOld);
    EXPECT_EQ(fs::status(real).permissions() & fs::perms::all,
              fs::perms::owner_read | fs::perms::owner_write);
    EXPECT_EQ(names_in(dir.path()), (std::set<std::string>{"real.pfm", "link.pfm"}));
}

TEST(OutputSafety, DevicesAreWrittenInPlace) {
    const TempDir dir;
    write_rays(dir.path() / "rays.bin", std::vector<Ray>(4, Ray{{0, 0, 5}, {0, 0, -1}, 0, 1e30f}));
    const auto result =
        test::run_cli("trace --scene builtin:cornell --rays " + (dir.path() / "rays.bin").string() +
                      " --out /dev/null --stats /dev/stdout");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("\"command\": \"trace\""), std::string::npos) << result.output;
}

TEST(OutputSafety, OutputsThatShareAFileAreRefusedBeforeAnyWork) {
    const TempDir dir;
    const fs::path rays = dir.path() / "rays.bin";
    write_rays(rays, std::vector<Ray>(4, Ray{{0, 0, 5}, {0, 0, -1}, 0, 1e30f}));
    const fs::path old = dir.write("old.pfm", kOld);
    fs::create_symlink(old, dir.path() / "alias.pfm");
    const std::string d = dir.path().string();
    const struct {
        std::string args, message;
    } cases[] = {
        {kRender + "--out " + d + "/x.pfm --stats " + d + "/x.pfm",
         "--out and --stats both name " + d + "/x.pfm"},
        {kRender + "--out " + d + "/sub/../x.pfm --stats " + d + "/x.pfm", "both name"},
        {kRender + "--out " + old.string() + " --stats " + d + "/alias.pfm", "both name"},
        {kRender + "--out " + old.string() + " --reference " + old.string(),
         "--out " + old.string() + " is the --reference input"},
        {"trace --scene builtin:cornell --rays " + rays.string() + " --out " + d +
             "/h.bin --stats " + d + "/h.bin",
         "--out and --stats both name"},
        {"trace --scene builtin:cornell --rays " + rays.string() + " --out " + rays.string(),
         "is the --rays input"},
        {"bench --scene builtin:cornell --json " + d + "/b --markdown " + d + "/b",
         "--json and --markdown both name"},
    };
    fs::create_directories(dir.path() / "sub");
    for (const auto& c : cases) {
        const auto result = test::run_cli(c.args);
        EXPECT_EQ(result.exit_code, 1) << c.args << "\n" << result.output;
        EXPECT_NE(result.output.find("edacrt: error: --"), std::string::npos) << result.output;
        EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n"
                                                                    << result.output;
        EXPECT_EQ(result.output.find("loaded"), std::string::npos) << "work before the refusal";
    }
    EXPECT_EQ(bytes_of(old), kOld);
    EXPECT_EQ(names_in(dir.path()),
              (std::set<std::string>{"rays.bin", "old.pfm", "alias.pfm", "sub"}));
    // Devices may be shared.
    const auto shared = test::run_cli("trace --scene builtin:cornell --rays " + rays.string() +
                                      " --out /dev/null --stats /dev/null");
    EXPECT_EQ(shared.exit_code, 0) << shared.output;
}

// No output may replace a file the command reads: the scene, every MTL library it loads, the
// animation file and the meshes it names, key frames, rays; through links too. The files named
// on the command line are refused before loading, those the scene names before any rendering.
TEST(OutputSafety, OutputsNeverReplaceTheCommandsInputs) {
    const TempDir dir;
    const std::string d = dir.path().string() + "/";
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib m.mtl\nusemtl red\nf 1 2 3\n";
    const std::string mtl = "newmtl red\nKd 1 0 0\n";
    const std::string anim = R"({"objects": [{"mesh": "tri.obj"}]})";
    dir.write("tri.obj", obj);
    dir.write("m.mtl", mtl);
    dir.write("anim.json", anim);
    dir.write("f_0000.obj", obj);  // key frames
    dir.write("f_0001.obj", obj);
    write_rays(dir.path() / "rays.bin", std::vector<Ray>(4, Ray{{0, 0, 5}, {0, 0, -1}, 0, 1e30f}));
    const std::string rays = bytes_of(dir.path() / "rays.bin");
    fs::create_symlink(dir.path() / "m.mtl", dir.path() / "link.mtl");
    fs::create_hard_link(dir.path() / "tri.obj", dir.path() / "hard.obj");
    const std::set<std::string> files = {"tri.obj",    "m.mtl",    "anim.json", "f_0000.obj",
                                         "f_0001.obj", "rays.bin", "link.mtl",  "hard.obj"};
    const std::string render = "render --width 8 --height 8 --spp 1 -q --out " + d + "x.png ";
    const struct {
        std::string args, message;
        bool before_loading;
    } cases[] = {
        {render + "--scene " + d + "tri.obj --stats " + d + "tri.obj",
         "--stats " + d + "tri.obj is the --scene input", true},
        {render + "--scene " + d + "tri.obj --stats " + d + "hard.obj",
         "--stats " + d + "hard.obj is the --scene input " + d + "tri.obj", true},
        {render + "--scene " + d + "tri.obj --stats " + d + "m.mtl",
         "--stats " + d + "m.mtl is the scene's input", false},
        {render + "--scene " + d + "tri.obj --stats " + d + "link.mtl",
         "--stats " + d + "link.mtl is the scene's input " + d + "m.mtl", false},
        {render + "--animate " + d + "anim.json --time 0 --stats " + d + "anim.json",
         "--stats " + d + "anim.json is the --animate input", true},
        {render + "--scene " + d + "anim.json --stats " + d + "tri.obj",
         "--stats " + d + "tri.obj is the scene's input", false},
        {render + "--sequence " + d + "f_%04d.obj --stats " + d + "f_0001.obj",
         "--stats " + d + "f_0001.obj is the scene's input", false},
        {"camera-rays --scene " + d + "tri.obj --width 4 --height 4 --out " + d + "tri.obj",
         "--out " + d + "tri.obj is the --scene input", true},
        {"trace --scene " + d + "tri.obj --rays " + d + "rays.bin --out " + d + "tri.obj",
         "--out " + d + "tri.obj is the --scene input", true},
        {"trace --scene " + d + "tri.obj --rays " + d + "rays.bin --out " + d + "link.mtl",
         "--out " + d + "link.mtl is the scene's input", false},
        {"accuracy --scene " + d + "tri.obj --rays 10 --stats " + d + "m.mtl",
         "--stats " + d + "m.mtl is the scene's input", false},
        {"bench --scene " + d +
             "tri.obj --width 8 --height 8 --repeat 1 --sets camera --spp 1 "
             "--methods bvh -q --json " +
             d + "tri.obj",
         "--json " + d + "tri.obj is the --scene input", true},
    };
    for (const auto& c : cases) {
        const auto result = test::run_cli(c.args);
        EXPECT_EQ(result.exit_code, 1) << c.args << "\n" << result.output;
        EXPECT_NE(result.output.find("edacrt: error: " + c.message), std::string::npos)
            << c.args << "\n"
            << result.output;
        EXPECT_NE(result.output.find(": writing it would replace what is read"), std::string::npos)
            << result.output;
        if (c.before_loading) {
            EXPECT_EQ(result.output.find("loaded"), std::string::npos) << "work before the refusal";
        }
        EXPECT_EQ(bytes_of(dir.path() / "tri.obj"), obj) << c.args;
        EXPECT_EQ(bytes_of(dir.path() / "m.mtl"), mtl) << c.args;
        EXPECT_EQ(bytes_of(dir.path() / "anim.json"), anim) << c.args;
        EXPECT_EQ(bytes_of(dir.path() / "f_0001.obj"), obj) << c.args;
        EXPECT_EQ(bytes_of(dir.path() / "rays.bin"), rays) << c.args;
        EXPECT_EQ(names_in(dir.path()), files) << c.args << ": nothing written";
    }
}

// bench --write-rays names its ray files after the scene and set: a report given one of those
// names would be replaced by it (or replace it), so it is refused before any work.
TEST(OutputSafety, BenchReportsMayNotNameAWrittenRayFile) {
    const TempDir dir;
    const std::string d = dir.path().string() + "/";
    dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const auto result = test::run_cli("bench --scene " + d +
                                      "tri.obj --width 8 --height 8 --repeat 1 --sets camera "
                                      "--spp 1 --methods bvh -q --write-rays " +
                                      d + "rays --json " + d + "rays/tri_camera-1spp.rays");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("edacrt: error: --json and --write-rays both name " + d +
                                 "rays/tri_camera-1spp.rays"),
              std::string::npos)
        << result.output;
    EXPECT_FALSE(fs::exists(dir.path() / "rays")) << "refused before any work";
}

// Under `ulimit -f` with SIGXFSZ at its default (kill), edacrt ignores the signal itself: the
// write fails with EFBIG and is reported, the old file kept and no temporary left.
TEST(OutputSafety, AFileSizeLimitIsReportedNotASilentKill) {
    const TempDir dir;
    const fs::path out = dir.write("old.png", kOld);
    const auto result =
        test::run_command("trap - XFSZ; ulimit -f 4; '" + test::cli_path().string() + "' " +
                          kRender + "--integrator primary -q --out " + out.string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("edacrt: error: " + out.string() + ": cannot write"),
              std::string::npos)
        << result.output;
    EXPECT_NE(result.output.find("File too large"), std::string::npos) << result.output;
    EXPECT_EQ(bytes_of(out), kOld);
    EXPECT_EQ(names_in(dir.path()), std::set<std::string>{"old.png"});
}

}  // namespace
}  // namespace edacrt
