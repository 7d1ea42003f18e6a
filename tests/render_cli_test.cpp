// edacrt render: integrators, PFM output, --reference, --time-budget, bad input, Ctrl-C.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>

#include "cli_runner.h"
#include "render/image.h"
#include "render/image_format.h"
#include "test_paths.h"

namespace edacrt {
namespace {

class RenderCli : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("edacrt_render_cli_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::filesystem::path dir_;
};

const std::string kSmall = "render --scene builtin:cornell --width 32 --height 24 ";

TEST_F(RenderCli, EveryIntegratorWritesAFiniteFloatImage) {
    for (const std::string integrator : {"primary", "ao", "path"}) {
        const auto result = test::run_cli(kSmall + "--spp 2 --integrator " + integrator +
                                          " --out " + path(integrator + ".pfm"));
        ASSERT_EQ(result.exit_code, 0) << result.output;
        const Image image = read_pfm(path(integrator + ".pfm"));
        ASSERT_EQ(image.width, 32);
        ASSERT_EQ(image.height, 24);
        double sum = 0.0;
        for (const glm::vec3& p : image.pixels) {
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            sum += double(p.x + p.y + p.z);
        }
        EXPECT_GT(sum, 0.0) << integrator;
    }
}

TEST_F(RenderCli, ReferenceErrorIsReportedAfterEveryPassAndFalls) {
    ASSERT_EQ(test::run_cli(kSmall + "--spp 64 --out " + path("ref.pfm")).exit_code, 0);
    const auto result = test::run_cli(
        kSmall + "--spp 16 --samples-per-pass 4 --seed 5 --reference " + path("ref.pfm") +
        " --stats " + path("stats.json") + " --out " + path("x.png"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const auto stats = nlohmann::json::parse(std::ifstream(path("stats.json")));
    // Passes of 4 samples, each reported.
    const auto& passes = stats["passes"];
    ASSERT_EQ(passes.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(passes[i]["spp"].get<int>(), 4 * int(i + 1));
    EXPECT_LT(passes[3]["rmse"].get<double>(), passes[0]["rmse"].get<double>());
    EXPECT_NE(result.output.find("rmse"), std::string::npos);
    // Passes of one sample; a last pass takes only what is left.
    const auto single = test::run_cli(kSmall + "--spp 6 --samples-per-pass 1 --stats " +
                                      path("one.json") + " --out " + path("x.png"));
    ASSERT_EQ(single.exit_code, 0) << single.output;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(path("one.json")))["passes"].size(), 6u);
    const auto uneven = test::run_cli(kSmall + "--spp 6 --samples-per-pass 4 --stats " +
                                      path("six.json") + " --out " + path("x.png"));
    ASSERT_EQ(uneven.exit_code, 0) << uneven.output;
    const auto six = nlohmann::json::parse(std::ifstream(path("six.json")));
    ASSERT_EQ(six["passes"].size(), 2u);
    EXPECT_EQ(six["passes"][1]["spp"].get<int>(), 6);
    // By default a small image takes all its samples in one pass (about 1M paths per pass).
    const auto whole =
        test::run_cli(kSmall + "--spp 6 --stats " + path("whole.json") + " --out " + path("x.png"));
    ASSERT_EQ(whole.exit_code, 0) << whole.output;
    const auto one_pass = nlohmann::json::parse(std::ifstream(path("whole.json")));
    ASSERT_EQ(one_pass["passes"].size(), 1u);
    EXPECT_EQ(one_pass["passes"][0]["spp"].get<int>(), 6);
    EXPECT_NE(test::run_cli(kSmall + "--samples-per-pass -1 --out " + path("x.png")).exit_code, 0);
    EXPECT_NE(test::run_cli(kSmall + "--samples-per-pass 1025 --out " + path("x.png")).exit_code,
              0);  // out of range, even where --spp is smaller
}

// --stats splits the trace time by batch kind: every batch, ray and second of the total is in
// exactly one kind, the kinds are the path tracer's (camera, then bounce:N and shadow:N), and
// each kind has one batch per pass.
TEST_F(RenderCli, BatchTimesAccountForEveryBatchOfThePath) {
    const auto result =
        test::run_cli(kSmall + "--spp 6 --samples-per-pass 2 --max-depth 3 --stats " +
                      path("s.json") + " --out " + path("x.png"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const auto stats = nlohmann::json::parse(std::ifstream(path("s.json")));
    const auto& kinds = stats.at("batch_times");
    ASSERT_FALSE(kinds.empty());
    EXPECT_EQ(kinds[0].at("batch"), "camera");
    std::uint64_t batches = 0, rays = 0;
    double seconds = 0.0;
    std::set<std::string> names;
    for (const auto& kind : kinds) {
        const std::string name = kind.at("batch");
        EXPECT_TRUE(names.insert(name).second) << name << " twice";
        EXPECT_TRUE(name == "camera" || name.starts_with("bounce:") || name.starts_with("shadow:"))
            << name;
        EXPECT_EQ(kind.at("batches").get<std::uint64_t>(), 3u) << name;  // 3 passes
        EXPECT_GT(kind.at("rays").get<std::uint64_t>(), 0u) << name;
        batches += kind.at("batches").get<std::uint64_t>();
        rays += kind.at("rays").get<std::uint64_t>();
        seconds += kind.at("seconds").get<double>();
    }
    EXPECT_EQ(names.count("bounce:3"), 1u);  // --max-depth 3: bounces 1-3
    EXPECT_EQ(names.count("bounce:4"), 0u);
    EXPECT_EQ(batches, stats.at("batches").get<std::uint64_t>());
    EXPECT_EQ(rays, stats.at("rays").get<std::uint64_t>());
    EXPECT_NEAR(seconds, stats.at("trace_seconds").get<double>(), 1e-9);
}

TEST_F(RenderCli, TimeBudgetStopsAProgressiveRender) {
    const auto result = test::run_cli(kSmall + "--time-budget 0.3 --stats " + path("s.json") +
                                      " --out " + path("x.png"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const auto stats = nlohmann::json::parse(std::ifstream(path("s.json")));
    // It stops after the first pass that reaches the budget: every earlier pass ended before it.
    const auto& passes = stats["passes"];
    ASSERT_GE(passes.size(), 1u);
    EXPECT_GE(passes.back()["seconds"].get<double>(), 0.3);
    for (std::size_t i = 0; i + 1 < passes.size(); ++i)
        EXPECT_LT(passes[i]["seconds"].get<double>(), 0.3) << "pass " << i;
    EXPECT_EQ(stats["spp"].get<int>(), passes.back()["spp"].get<int>());
    // Passes of 4 samples by default under a time budget, which a pass may overshoot.
    EXPECT_LE(stats["spp"].get<std::size_t>(), 4 * passes.size());
}

TEST_F(RenderCli, BadInputFailsWithAClearMessage) {
    std::ofstream(path("bad.pfm")) << "P6\n1 1\n255\n";
    std::ofstream(path("short.pfm")) << "PF\n32 24\n-1.0\n" << std::string(100, '\0');
    ASSERT_EQ(test::run_cli(kSmall + "--spp 1 --out " + path("ref.pfm")).exit_code, 0);
    const struct {
        std::string args, message;
    } cases[] = {
        {kSmall + "--integrator magic", "unknown integrator 'magic'"},
        {kSmall + "--primary magic --integrator primary", "unknown primary shading"},
        {kSmall + "--max-depth -1", "max depth"},
        {kSmall + "--ao-samples 0", "ao samples"},
        {kSmall + "--time-budget -1", "--time-budget"},
        {kSmall + "--exposure nan", "exposure must be a finite number of stops in [-64, 64]"},
        {kSmall + "--exposure -inf", "exposure must be a finite number of stops"},
        {kSmall + "--exposure 1000", "exposure must be a finite number of stops"},
        {kSmall + "--tone-map magic", "unknown tone map"},
        {kSmall + "--embree-mode magic", "unknown Embree mode"},
        {kSmall + "--reference " + path("bad.pfm"), "not a colour PFM"},
        {kSmall + "--reference /no/such.pfm", "cannot read image (No such file or directory)"},
        {kSmall + "--reference " + path("short.pfm"), "PFM data ends early"},
        {"render --scene builtin:cornell --width 16 --height 16 --reference " + path("ref.pfm"),
         "the reference is 32x24"},
    };
    for (const auto& c : cases) {
        const auto result = test::run_cli(c.args + " --out " + path("x.png"));
        EXPECT_NE(result.exit_code, 0) << c.args;
        EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n"
                                                                    << result.output;
    }
}

TEST_F(RenderCli, ARenderThatCannotFitIsRefusedUpFront) {
    // The limit is set low so that the test does not depend on this machine's memory.
    const auto result = test::run_command(
        "EDACRT_MEMORY_LIMIT=1000000000 '" + test::cli_path().string() +
        "' render --scene builtin:cornell --width 16384 --height 16384 --out " + path("x.png"));
    EXPECT_EQ(result.exit_code, 1) << result.output;
    // Film 24 bytes per pixel, a pass's 4 samples 48, the image (tone-mapped in place) 12, the
    // PNG's buffers 12 and a wavefront within 1 GiB (4 per pixel here): 99 (the peak RSS
    // measured 55 with passes of one sample, against the 60 estimated then).
    EXPECT_NE(result.output.find("edacrt: error: a 16384x16384 path render needs about 26.8 GB "
                                 "of memory (99 bytes per pixel), more than the 1.0 GB of "
                                 "EDACRT_MEMORY_LIMIT; choose a smaller size"),
              std::string::npos)
        << result.output;
    EXPECT_EQ(result.output.find("loaded"), std::string::npos) << "refused before any work";
}

// A folder that cannot be made (a file is in the way) is an input error found before the
// render, not an internal error after it.
TEST_F(RenderCli, AnOutputFolderThatCannotBeMadeIsRefusedBeforeRendering) {
    std::ofstream(path("file")) << "in the way";
    for (const std::string& args :
         {"--out " + path("file/sub/x.png"),
          "--out " + path("x.png") + " --stats " + path("file/stats.json")}) {
        const auto result = test::run_cli(kSmall + "--spp 1 " + args);
        EXPECT_EQ(result.exit_code, 1) << args << "\n" << result.output;
        EXPECT_NE(result.output.find("edacrt: error: "), std::string::npos) << result.output;
        EXPECT_NE(result.output.find(path("file/")), std::string::npos) << args << "\n"
                                                                        << result.output;
        EXPECT_EQ(result.output.find("loaded"), std::string::npos) << "refused before any work";
    }
}

TEST_F(RenderCli, WriteErrorsFailTheCommand) {
    // /dev/full takes the open and fails the writes; small outputs fail only at the close.
    std::filesystem::create_symlink("/dev/full", path("full.pfm"));
    std::filesystem::create_symlink("/dev/full", path("full.png"));
    const struct {
        std::string args, message;
    } cases[] = {
        {"--out " + path("full.png"), "full.png: cannot write PNG (No space left on device)"},
        {"--out " + path("full.pfm"), "full.pfm: cannot write PFM (No space left on device)"},
        {"--out " + path("x.png") + " --stats /dev/full",
         "/dev/full: cannot write statistics (No space left on device)"},
    };
    for (const auto& c : cases) {
        const auto result = test::run_cli(kSmall + "--spp 1 " + c.args);
        EXPECT_EQ(result.exit_code, 1) << c.args << "\n" << result.output;
        EXPECT_NE(result.output.find("edacrt: error: "), std::string::npos) << result.output;
        EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n"
                                                                    << result.output;
    }
    // The report on stdout is checked too (the subshell keeps stderr on the pipe).
    const auto report = test::run_command("('" + test::cli_path().string() + "' " + kSmall +
                                          "--spp 1 --out " + path("x.png") + " >/dev/full)");
    EXPECT_EQ(report.exit_code, 1) << report.output;
    EXPECT_NE(report.output.find("edacrt: error: cannot write to standard output"),
              std::string::npos)
        << report.output;
}

TEST_F(RenderCli, ACameraWhoseArithmeticOverflowsIsRefusedEverywhere) {
    // eye - look_at overflows float: every ray direction was NaN (bvh crashed, the others
    // rendered black and exited 0, camera-rays wrote NaN rays).
    const std::string view = " --eye 3e38,0,0 --look-at -3e38,0,0 ";
    for (const std::string method : {"bvh", "edacrt", "naive"}) {
        const auto result = test::run_cli(kSmall + "--spp 1 --method " + method + view + "--out " +
                                          path("overflow.png"));
        EXPECT_EQ(result.exit_code, 1) << result.output;
        EXPECT_NE(result.output.find("camera: the view direction cannot be normalised"),
                  std::string::npos)
            << result.output;
        EXPECT_FALSE(std::filesystem::exists(path("overflow.png")));
    }
    for (const std::string& command : std::vector<std::string>{
             "camera-rays --scene builtin:cornell --width 4 --height 4 --out " + path("r.rays"),
             "info builtin:cornell"}) {
        const auto result = test::run_cli(command + view);
        EXPECT_EQ(result.exit_code, 1) << command << ": " << result.output;
        EXPECT_NE(result.output.find("camera:"), std::string::npos) << result.output;
    }
}

TEST_F(RenderCli, AFaceOfAHundredThousandCornersIsTracedByEveryMethod) {
    // The OBJ loader makes a fan of thin triangles from it, which once drove the recursions
    // 13,000 levels deep, past the stack (edacrt from 60k corners, dacrt from 300k).
    {
        std::ofstream obj(path("fan.obj"));
        const int corners = 100000;
        for (int k = 0; k < corners; ++k) {
            const double a = 2.0 * M_PI * k / corners;
            obj << "v " << std::cos(a) << " " << std::sin(a) << " 0\n";
        }
        obj << "f";
        for (int k = 1; k <= corners; ++k) obj << " " << k;
        obj << "\n";
    }
    for (const std::string method : {"edacrt", "dacrt", "bvh"}) {
        const auto result =
            test::run_cli("render --scene " + path("fan.obj") + " --width 48 --height 48 " +
                          "--spp 1 --integrator primary --eye 0.3,0.2,3 --look-at 0,0,0 " +
                          "--method " + method + " --out " + path(method + ".pfm"));
        ASSERT_EQ(result.exit_code, 0) << method << ": " << result.output;
        // The disc fills the middle of the image and misses the corners.
        const Image image = read_pfm(path(method + ".pfm"));
        const auto pixel = [&](int x, int y) { return image.pixels[std::size_t(y * 48 + x)]; };
        EXPECT_GT(pixel(24, 24).x, 0.0f) << method;
        EXPECT_EQ(pixel(0, 0).x, 0.0f) << method;
    }
}

/// Waits up to `limit` for an interrupted render and checks that it exited with status 130;
/// returns its output.
std::string expect_interrupted_exit(test::BackgroundCli& render, std::chrono::seconds limit) {
    const auto status = render.wait(limit);
    const std::string output = render.output();
    EXPECT_TRUE(status) << "still running " << limit.count() << " s after Ctrl-C";
    if (!status) return output;
    EXPECT_TRUE(WIFEXITED(*status)) << output;
    EXPECT_EQ(WEXITSTATUS(*status), 130) << output;
    return output;
}

// Ctrl-C keeps the passes completed: the image (and --stats, without the untimed detail trace)
// is written with the samples so far and the command exits 130 saying how many.
TEST_F(RenderCli, InterruptWritesTheSamplesSoFarAndExits130) {
    test::BackgroundCli render(kSmall + "--spp 100000 --samples-per-pass 1 --stats " +
                                   path("s.json") + " --out " + path("x.png"),
                               path("output.txt"));
    ASSERT_TRUE(render.wait_for_output("/100000 spp", std::chrono::seconds(60))) << render.output();
    render.signal(SIGINT);
    const std::string output = expect_interrupted_exit(render, std::chrono::seconds(60));
    if (HasFailure()) return;
    const auto stats = nlohmann::json::parse(std::ifstream(path("s.json")));
    const int spp = stats["spp"].get<int>();
    EXPECT_GE(spp, 1);
    EXPECT_LT(spp, 100000);
    EXPECT_TRUE(stats["interrupted"].get<bool>());
    EXPECT_FALSE(stats.contains("detail"));
    EXPECT_NE(output.find("edacrt: interrupted: wrote " + path("x.png") + " with " +
                          std::to_string(spp) + " of 100000 samples per pixel"),
              std::string::npos)
        << output;
    const Image image = load_image(path("x.png"));
    EXPECT_EQ(image.width, 32);
    EXPECT_EQ(image.height, 24);
}

// Interrupted before the first pass ends (the naive method on 20k triangles takes seconds a
// batch): nothing is written, and it says so. Passes of 4 samples: by default this small image
// takes all 64 in one pass, whose batches would outlast the test under the sanitizers.
TEST_F(RenderCli, InterruptBeforeTheFirstPassWritesNothing) {
    test::BackgroundCli render(
        "render --scene builtin:sphere:subdiv=5 --method naive --threads 1 --width 64 "
        "--height 48 --spp 64 --samples-per-pass 4 --stats " +
            path("s.json") + " --out " + path("x.png"),
        path("output.txt"));
    ASSERT_TRUE(render.wait_for_output("loaded builtin:sphere", std::chrono::seconds(60)))
        << render.output();
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    render.signal(SIGINT);
    const std::string output = expect_interrupted_exit(render, std::chrono::seconds(120));
    if (HasFailure()) return;
    EXPECT_NE(output.find("edacrt: interrupted: no pass completed, nothing written"),
              std::string::npos)
        << output;
    EXPECT_FALSE(std::filesystem::exists(path("x.png")));
    EXPECT_FALSE(std::filesystem::exists(path("s.json")));
}

// A second Ctrl-C does not wait for the batch in progress (the naive method on 20k triangles:
// about ten seconds a batch): the command exits 130 at once.
TEST_F(RenderCli, ASecondInterruptExitsAtOnce) {
    // One pass of 64 spp is one wavefront of 786k paths against 20k triangles by brute force:
    // minutes before the first Ctrl-C could stop it at the next batch, so only the second one
    // can end it, without the "interrupted:" report.
    test::BackgroundCli render(
        "render --scene builtin:sphere:subdiv=5 --method naive --threads 1 --width 128 "
        "--height 96 --spp 64 --samples-per-pass 64 --out " +
            path("x.png"),
        path("output.txt"));
    ASSERT_TRUE(render.wait_for_output("loaded builtin:sphere", std::chrono::seconds(60)))
        << render.output();
    // Inside the batch: a Ctrl-C before it (the camera rays take about a second under the
    // sanitizers on a loaded machine) stops the render at its first batch, with the report.
    std::this_thread::sleep_for(std::chrono::seconds(3));
    render.signal(SIGINT);
    // Signals do not queue: a second Ctrl-C sent before the first was delivered (a loaded
    // machine may not run the process for 50 ms) merges with it. So Ctrl-C again each second
    // until it ends.
    for (int second = 0; second < 5 && !render.wait(std::chrono::seconds(1)); ++second)
        render.signal(SIGINT);
    const std::string output = expect_interrupted_exit(render, std::chrono::seconds(1));
    if (HasFailure()) return;
    EXPECT_EQ(output.find("interrupted:"), std::string::npos) << output;
    EXPECT_FALSE(std::filesystem::exists(path("x.png")));
}

// An animation stops after the frame in progress, which is written.
TEST_F(RenderCli, InterruptStopsAnAnimationAfterTheCurrentFrame) {
    test::BackgroundCli render(
        "render --scene builtin:sphere:subdiv=3 --animate wave --frames 0:4 --width 32 "
        "--height 24 --sky 1,1,1 --spp 100000 --samples-per-pass 1 --out " +
            path("f%d.png"),
        path("output.txt"));
    ASSERT_TRUE(render.wait_for_output("/100000 spp", std::chrono::seconds(60))) << render.output();
    render.signal(SIGINT);
    const std::string output = expect_interrupted_exit(render, std::chrono::seconds(60));
    if (HasFailure()) return;
    EXPECT_NE(output.find("edacrt: interrupted: frame 0: wrote " + path("f0.png") + " with "),
              std::string::npos)
        << output;
    EXPECT_NE(output.find("samples per pixel; 4 later frames not rendered"), std::string::npos)
        << output;
    EXPECT_EQ(load_image(path("f0.png")).width, 32);
    EXPECT_FALSE(std::filesystem::exists(path("f1.png")));
}

}  // namespace
}  // namespace edacrt
