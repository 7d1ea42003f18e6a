// edacrt render --time/--frames and bench --dynamic: the files and rows they promise, the same
// image for the same time with any update mode, and clear errors for bad animation flags.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "cli_runner.h"
#include "render/image.h"
#include "render/sampler.h"
#include "temp_dir.h"
#include "test_paths.h"

namespace edacrt {
namespace {

using test::TempDir;

std::string spot() { return (test::source_dir() / "assets/spot/spot.obj").string(); }

const std::string kSmall = "render --width 32 --height 24 --spp 1 --integrator primary ";

using test::bytes_of;

TEST(AnimationCli, FramesWriteOneImagePerFrame) {
    const TempDir dir;
    const auto result =
        test::run_cli(kSmall + "--scene " + spot() + " --animate wave:amplitude=0.1 --frames 2:4 " +
                      "--fps 8 --method bvh --update refit --out " +
                      (dir.path() / "anim/frame_%04d.png").string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    for (const char* name : {"frame_0002.png", "frame_0003.png", "frame_0004.png"})
        EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / "anim" / name)) << name;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path() / "anim"), {}), 3);
    EXPECT_NE(result.output.find("frame 3 (t = 0.375 s): bvh refitted"), std::string::npos)
        << result.output;
    EXPECT_NE(result.output.find("frame 2 (t = 0.25 s): bvh rebuilt"), std::string::npos);
    // Frames differ; a frame rendered alone at its time, rebuilt by another method, is the same.
    EXPECT_NE(bytes_of(dir.path() / "anim/frame_0002.png"),
              bytes_of(dir.path() / "anim/frame_0003.png"));
    const auto alone =
        test::run_cli(kSmall + "--scene " + spot() + " --animate wave:amplitude=0.1 --time 0.375 " +
                      "--method edacrt --out " + (dir.path() / "alone.png").string());
    ASSERT_EQ(alone.exit_code, 0) << alone.output;
    EXPECT_EQ(bytes_of(dir.path() / "alone.png"), bytes_of(dir.path() / "anim/frame_0003.png"));
}

TEST(AnimationCli, BundledKeyframedAnimationRendersWithoutAScene) {
    const TempDir dir;
    const auto result = test::run_cli(
        kSmall + "--animate " +
        (test::source_dir() / "assets/animations/spot-and-teapot.anim.json").string() +
        " --time 1.5 --stats " + (dir.path() / "stats.json").string() + " --out " +
        (dir.path() / "x.pfm").string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const auto stats = nlohmann::json::parse(std::ifstream(dir.path() / "stats.json"));
    EXPECT_EQ(stats["triangles"], 12 + 5856 + 6320);
    EXPECT_EQ(stats["time"], 1.5);
    EXPECT_EQ(stats["scene_update"]["work"], "none");
    EXPECT_EQ(read_pfm(dir.path() / "x.pfm").width, 32);
}

// --shutter: passes at times spread over the shutter, averaged. A zero shutter is no blur; a
// shutter over a still moment of the animation (past the last key) changes nothing; otherwise
// the image is the mean of the frames at the passes' times.
TEST(AnimationCli, ShutterAveragesPassesOverTimeIntoMotionBlur) {
    const TempDir dir;
    const std::string animation =
        "--animate " +
        (test::source_dir() / "assets/animations/spot-and-teapot.anim.json").string();
    const auto render = [&](const std::string& args, const std::string& name) {
        const auto result =
            test::run_cli("render --width 48 --height 32 --integrator primary " + animation + " " +
                          args + " --out " + (dir.path() / name).string());
        EXPECT_EQ(result.exit_code, 0) << args << "\n" << result.output;
        return read_pfm(dir.path() / name);
    };
    const Image sharp = render("--time 1 --spp 2", "sharp.pfm");
    EXPECT_TRUE(render("--time 1 --spp 2 --shutter 0", "zero.pfm").pixels == sharp.pixels);
    const Image blurred = render("--time 1 --spp 2 --shutter 0.5", "blur.pfm");
    EXPECT_FALSE(blurred.pixels == sharp.pixels);
    // Passes of one sample whatever --samples-per-pass says: each is its own time.
    EXPECT_TRUE(render("--time 1 --spp 2 --shutter 0.5 --samples-per-pass 8", "blur8.pfm").pixels ==
                blurred.pixels);
    // Two passes of one sample: t = 1, then t = 0.75 (render/sampler.h; the viewer's worker
    // test checks the average sample by sample).
    EXPECT_EQ(shutter_time(1.0, 0.5, 0), 1.0);
    EXPECT_EQ(shutter_time(1.0, 0.5, 1), 0.75);
    // After the last key (4 s) the objects stand still: blur changes nothing there.
    EXPECT_TRUE(render("--time 5 --spp 2 --shutter 0.5", "still_blur.pfm").pixels ==
                render("--time 5 --spp 2", "still.pfm").pixels);
}

TEST(AnimationCli, BadAnimationFlagsAreErrors) {
    const TempDir dir;
    const std::string out = " --out " + (dir.path() / "f_%02d.png").string();
    const std::string scene = "--scene " + spot() + " --animate wave ";
    // Bad flag values and combinations are usage errors (2); what loading finds, bad input (1).
    const auto expect_error = [&](const std::string& args, const std::string& message,
                                  int status = 2) {
        const auto result = test::run_cli(kSmall + args);
        EXPECT_EQ(result.exit_code, status) << args << "\n" << result.output;
        EXPECT_NE(result.output.find(message), std::string::npos) << args << "\n" << result.output;
    };
    expect_error(scene + "--frames 3:1" + out, "the last frame is before the first");
    expect_error(scene + "--frames 1-3" + out, "expected A:B");
    expect_error(scene + "--frames 0:x" + out, "frame numbers are integers");
    expect_error(scene + "--frames 0:2 --out " + (dir.path() / "one.png").string(),
                 "has no frame number");
    expect_error(scene + "--time 1" + out, "has a frame number but one image is rendered");
    expect_error(scene + "--time 1 --frames 0:1" + out, "give one");
    expect_error(scene + "--time nan --out x.png", "--time must be a finite number");
    expect_error(scene + "--frames 0:1 --fps 0" + out, "--fps must be a number");
    expect_error(scene + "--update sideways --out x.png", "unknown scene update 'sideways'");
    expect_error(scene + "--shutter -0.1 --out x.png", "--shutter must be");
    expect_error(scene + "--shutter inf --out x.png", "--shutter must be");
    expect_error(scene + "--frames 0:1 --stats s.json" + out, "for one image");
    expect_error("--scene " + spot() + " --animate wave:amplitude=99 --out x.png", "amplitude", 1);
    expect_error("--animate wave --out x.png", "deforms a scene: name one", 1);
    expect_error("--out x.png", "no scene");
    expect_error(
        "--scene " + spot() + " --sequence " + (dir.path() / "k%d.obj").string() + " --out x.png",
        "names its own geometry", 1);
    expect_error("--sequence " + (dir.path() / "k%d.obj").string() + " --out x.png", "no file in",
                 1);
    expect_error("--sequence a%d.obj --animate wave --out x.png", "give one");
    // The first frame renders before the broken key frame is read: an error, not a skip.
    dir.write("k1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    dir.write("k2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    expect_error("--sequence " + (dir.path() / "k%d.obj").string() + " --frames 0:1" + out,
                 "k2.obj: 2 triangles, other than the first key frame", 1);
}

// A number JSON can write but a double cannot hold: an input error naming the file.
TEST(AnimationCli, AnOutOfRangeNumberInAnAnimationFileIsAnInputError) {
    const TempDir dir;
    const auto file = dir.write(
        "big.json", R"({"objects": [{"mesh": "builtin:cornell", "keys": [{"time": 1e999}]}]})");
    const auto result = test::run_cli(kSmall + "--animate " + file.string() + " --out " +
                                      (dir.path() / "x.png").string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("edacrt: error: " + file.string() + ": not valid JSON"),
              std::string::npos)
        << result.output;
}

// A key frame that is a symlink to itself: an input error naming it, not an internal error.
TEST(AnimationCli, ASymlinkLoopInASequenceFolderIsAnInputError) {
    const TempDir dir;
    dir.write("k1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    std::filesystem::create_symlink("k2.obj", dir.path() / "k2.obj");
    const auto result = test::run_cli(kSmall + "--sequence " + (dir.path() / "k%d.obj").string() +
                                      " --out " + (dir.path() / "x.png").string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("edacrt: error: sequence "), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("cannot read " + (dir.path() / "k2.obj").string() + " in " +
                                 dir.path().string()),
              std::string::npos)
        << result.output;
}

// An animation file as --scene is read as --animate (as the viewer reads it); .JSON is .json;
// commands that take no animation say to use --animate instead of parsing JSON as OBJ.
TEST(AnimationCli, AnAnimationFileAsSceneIsAnimatedAndUpperCaseJsonIsJson) {
    const TempDir dir;
    const std::string bundled =
        (test::source_dir() / "assets/animations/spot-and-teapot.anim.json").string();
    const auto render = [&](const std::string& args, const std::string& name) {
        const auto result =
            test::run_cli(kSmall + args + " --time 1.5 --out " + (dir.path() / name).string());
        EXPECT_EQ(result.exit_code, 0) << args << "\n" << result.output;
        return bytes_of(dir.path() / name);
    };
    EXPECT_EQ(render("--scene " + bundled, "scene.png"), render("--animate " + bundled, "a.png"));
    const std::string upper =
        dir.write("box.JSON", R"({"objects": [{"mesh": "builtin:cornell", "keys": [{"time": 0}, )"
                              R"({"time": 2, "translate": [0.1, 0, 0]}]}]})")
            .string();
    EXPECT_EQ(render("--scene " + upper, "upper_scene.png"),
              render("--animate " + upper, "upper.png"));
    const auto info = test::run_cli("info " + upper);
    EXPECT_EQ(info.exit_code, 1) << info.output;
    EXPECT_NE(info.output.find(upper + ": an animation file, not a scene: give it with --animate"),
              std::string::npos)
        << info.output;
}

// --frames, --time and --shutter choose moments of an animation: a still scene refuses them.
TEST(AnimationCli, AnimationFlagsWithoutAnAnimationAreRefused) {
    const TempDir dir;
    for (const std::string flag : {"--frames 0:1", "--time 1", "--shutter 0.1"}) {
        const auto result = test::run_cli(kSmall + "--scene " + spot() + " " + flag + " --out " +
                                          (dir.path() / "x_%d.png").string());
        EXPECT_EQ(result.exit_code, 2) << flag << "\n" << result.output;  // a usage error
        EXPECT_NE(result.output.find("edacrt: error: " + flag.substr(0, flag.find(' ')) +
                                     " is for an animation"),
                  std::string::npos)
            << flag << "\n"
            << result.output;
    }
}

// %% in --out is a literal %, in folders and in a single image's name.
TEST(AnimationCli, DoublePercentInOutIsALiteralPercent) {
    const TempDir dir;
    const std::string still = "--scene " + spot();
    const std::string animated = still + " --animate wave ";
    const struct {
        std::string args, out, written;
    } cases[] = {
        {still, "100%%/one%%.png", "100%/one%.png"},
        {animated + "--frames 1:1", "a%%b/f%%_%02d.png", "a%b/f%_01.png"},
    };
    for (const auto& c : cases) {
        const auto result =
            test::run_cli(kSmall + c.args + " --out " + (dir.path() / c.out).string());
        EXPECT_EQ(result.exit_code, 0) << c.args << "\n" << result.output;
        EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / c.written)) << c.written << "\n"
                                                                              << result.output;
    }
}

TEST(AnimationCli, DynamicBenchReportsUpdateAndTraceForEveryMethod) {
    const TempDir dir;
    const auto result = test::run_cli(
        "bench --dynamic --scene spot --width 24 --height 16 --frames 2 --spp 1,4 "
        "--rays-per-triangle 0.05,0.5 --json " +
        (dir.path() / "d.json").string() + " --markdown " + (dir.path() / "d.md").string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const auto json = nlohmann::json::parse(std::ifstream(dir.path() / "d.json"));
    EXPECT_TRUE(json["agreement_ok"].get<bool>());
    EXPECT_EQ(json["scenes"][0]["animation"],
              "wave:amplitude=0.02,wavelength=0.25,period=1,axis=y,direction=x");
    std::set<std::string> methods = {"edacrt", "edacrt/presplit-0", "dacrt", "bvh/rebuild",
                                     "bvh/refit"};
#ifdef EDACRT_HAS_EMBREE
    methods.insert({"embree/rebuild", "embree/dynamic", "embree/refit"});
#endif
    std::set<std::pair<std::string, std::string>> seen;
    std::set<double> sweep;
    for (const auto& row : json["results"]) {
        const std::string method = row["method"];
        seen.insert({row["set"], method});
        if (row["set"] == "sweep") sweep.insert(row["rays_per_triangle"].get<double>());
        ASSERT_EQ(row["update_seconds"].size(), 2u);
        ASSERT_EQ(row["trace_seconds"].size(), 2u);
        EXPECT_EQ(row["agreement"]["disagreements"], 0) << row.dump();
        const std::string work = row["update_work"];
        const std::string expected = method.starts_with("edacrt") || method == "dacrt" ? "none"
                                     : method.ends_with("refit")                       ? "refitted"
                                                                                       : "rebuilt";
        EXPECT_EQ(work, expected) << method;
    }
    for (const std::string set : {"camera-1spp", "camera-4spp", "sweep"})
        for (const std::string& m : methods) EXPECT_TRUE(seen.count({set, m})) << set << " " << m;
    EXPECT_EQ(seen.size(), 3 * methods.size());
    EXPECT_EQ(sweep.size(), 2u);
    EXPECT_EQ(json["crossovers"].size(), methods.size() - 3);  // those with a structure
    const std::string markdown = bytes_of(dir.path() / "d.md");
    EXPECT_NE(markdown.find("| spot | camera-4spp |"), std::string::npos);
    EXPECT_NE(markdown.find("faster than edacrt from"), std::string::npos);

    const auto bad = test::run_cli("bench --dynamic --scene spot --frames 0");
    EXPECT_EQ(bad.exit_code, 2);  // a usage error
    EXPECT_NE(bad.output.find("--frames must be from 1 to 1000"), std::string::npos);
    const auto negative = test::run_cli("bench --dynamic --scene spot --rays-per-triangle -1");
    EXPECT_EQ(negative.exit_code, 2);
    EXPECT_NE(negative.output.find("--rays-per-triangle"), std::string::npos);
}

}  // namespace
}  // namespace edacrt
