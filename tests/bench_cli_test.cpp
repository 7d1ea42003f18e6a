// edacrt bench: every method and ray set in the JSON, the methods agree, bad parameters fail
// with a message. Tiny images and one repetition keep it fast.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "cli_runner.h"
#include "temp_dir.h"
#include "test_paths.h"

namespace edacrt {
namespace {

class BenchCli : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("edacrt_bench_cli_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    nlohmann::json read_json(const std::string& name) const {
        std::ifstream in(path(name));
        return nlohmann::json::parse(in);
    }

    std::filesystem::path dir_;
};

TEST_F(BenchCli, EveryMethodAndSetAgree) {
    const auto result = test::run_cli("bench --scene cornell --width 24 --height 16 --repeat 1 " +
                                      std::string("--json ") + path("bench.json") + " --markdown " +
                                      path("bench.md"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const nlohmann::json json = read_json("bench.json");
    EXPECT_TRUE(json["agreement_ok"].get<bool>());
    EXPECT_FALSE(json["machine"]["cpu"].get<std::string>().empty());
    EXPECT_FALSE(json["machine"]["date"].get<std::string>().empty());
    ASSERT_EQ(json["scenes"].size(), 1u);
    EXPECT_EQ(json["scenes"][0]["shadow_light"], "emissive triangles");

    std::set<std::string> methods = {"edacrt", "dacrt", "bvh"};
#ifdef EDACRT_HAS_EMBREE
    methods.insert({"embree/packet8", "embree/single", "embree/stream"});
#endif
    const std::set<std::string> sets = {"camera-1spp", "camera-4spp", "camera-16spp",
                                        "diffuse",     "ao",          "shadow"};
    std::set<std::pair<std::string, std::string>> seen;
    for (const nlohmann::json& row : json["results"]) {
        seen.insert({row["set"].get<std::string>(), row["method"].get<std::string>()});
        EXPECT_EQ(row["agreement"]["disagreements"], 0) << row.dump();
        EXPECT_GT(row["mrays_per_second_frame"].get<double>(), 0.0) << row.dump();
        EXPECT_EQ(row["trace_seconds"].size(), 1u);
        EXPECT_GT(row["working_bytes"].get<double>(), 0.0) << row.dump();
        const bool embree = row["method"].get<std::string>().starts_with("embree");
        EXPECT_EQ(row["triangle_tests_per_ray"].is_null(), embree) << row.dump();
        EXPECT_EQ(row["frame_time_per_best_embree"].is_null(), !methods.contains("embree/packet8"));
        const std::size_t pixels = 24 * 16;
        if (row["set"] == "camera-16spp") {
            EXPECT_EQ(row["rays"], 16 * pixels);
        }
        if (row["set"] == "ao") {
            EXPECT_EQ(row["query"], "any");
        }
    }
    for (const std::string& set : sets)
        for (const std::string& method : methods)
            EXPECT_TRUE(seen.contains({set, method})) << set << " " << method;
    EXPECT_NE(test::bytes_of(path("bench.md")).find("| scene | set |"), std::string::npos);
    EXPECT_NE(result.output.find("frame ms"), std::string::npos) << result.output;
}

// A spec's settings reach its tracer: variants that are the same settings written two ways
// make the same (deterministic, one thread) counters, and a changed setting changes them.
TEST_F(BenchCli, VariantsTakeTheirOwnSettings) {
    const char* variants[] = {"edacrt",
                              "edacrt:preset=paper",
                              "edacrt:small-nodes=every-ray:second-child=after-first:presplit=0:"
                              "leaf-tris=4:leaf-tris-rays=0",
                              "edacrt:preset=dacrt",
                              "dacrt",
                              "edacrt:leaf-tris=2:leaf-rays=2",
                              "bvh",
                              "bvh:max-leaf=1:bins=4:c-t=2"};
    std::string methods;
    for (const char* v : variants) methods += std::string(methods.empty() ? "" : ",") + v;
    const auto result = test::run_cli(
        "bench --scene teapot --sets camera,shadow --spp 1 --width 48 --height 32 --repeat 1 "
        "--threads 1 --methods " +
        methods + " --json " + path("variants.json"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const nlohmann::json json = read_json("variants.json");
    EXPECT_TRUE(json["agreement_ok"].get<bool>());
    std::map<std::pair<std::string, std::string>, std::pair<double, double>> tests;
    for (const nlohmann::json& row : json["results"])
        tests[{row["set"], row["method"]}] = {row["box_tests_per_ray"].get<double>(),
                                              row["triangle_tests_per_ray"].get<double>()};
    for (const std::string set : {"camera-1spp", "shadow"}) {
        for (const char* v : variants) ASSERT_TRUE(tests.contains({set, v})) << set << " " << v;
        const auto of = [&](const char* v) { return tests.at({set, v}); };
        EXPECT_EQ(of("edacrt:preset=paper"),
                  of("edacrt:small-nodes=every-ray:second-child=after-first:presplit=0:"
                     "leaf-tris=4:leaf-tris-rays=0"));
        EXPECT_EQ(of("dacrt"), of("edacrt:preset=dacrt"));
        EXPECT_NE(of("edacrt"), of("edacrt:preset=paper")) << set;
        EXPECT_LT(of("edacrt:leaf-tris=2:leaf-rays=2").second, of("edacrt").second) << set;
        EXPECT_NE(of("bvh"), of("bvh:max-leaf=1:bins=4:c-t=2")) << set;
    }
}

TEST_F(BenchCli, ThreadSweepReportsScaling) {
    const auto result = test::run_cli(
        "bench --scene builtin:sphere:subdiv=3 --sets camera --spp 1 --methods bvh,naive "
        "--width 16 --height 16 --repeat 1 --threads 2 --thread-sweep --json " +
        path("sweep.json"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("warning: naive"), std::string::npos) << result.output;
    std::set<int> threads;
    const nlohmann::json json = read_json("sweep.json");
    for (const nlohmann::json& row : json["results"]) {
        threads.insert(row["threads"].get<int>());
        EXPECT_EQ(row["scaling_1_thread_over_n"].is_null(), row["threads"] == 1) << row.dump();
    }
    EXPECT_EQ(threads, (std::set<int>{1, 2}));
}

TEST_F(BenchCli, AbsentScenesAreSkipped) {
    const auto result = test::run_command(
        "EDACRT_SCENES=" + path("no-such-dir") + " '" + test::cli_path().string() +
        "' bench --sets camera --spp 1 --methods bvh --width 8 --height 8 "
        "--repeat 1 --json " +
        path("skip.json"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("skipping bunny"), std::string::npos) << result.output;
    std::set<std::string> names;
    const nlohmann::json json = read_json("skip.json");
    for (const nlohmann::json& scene : json["scenes"])
        names.insert(scene["name"].get<std::string>());
    EXPECT_EQ(names, (std::set<std::string>{"cornell", "spot", "teapot"}));
}

TEST_F(BenchCli, InteriorsAreViewedFromInside) {
    if (const std::string why = test::missing_scene("sponza/sponza.obj"); !why.empty())
        GTEST_SKIP() << why;
    const auto result = test::run_cli(
        "bench --scene sponza --scene spot --sets camera --spp 1 --methods bvh --width 8 "
        "--height 8 --repeat 1 --json " +
        path("views.json"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const nlohmann::json scenes = read_json("views.json")["scenes"];
    ASSERT_EQ(scenes.size(), 2u);
    EXPECT_TRUE(scenes[0]["view"]["inside"].get<bool>()) << scenes[0].dump();
    EXPECT_FALSE(scenes[1]["view"]["inside"].get<bool>()) << scenes[1].dump();
}

TEST_F(BenchCli, WritesEachSetsRaysForTrace) {
    const auto result = test::run_cli(
        "bench --scene cornell --width 12 --height 8 --spp 1 --sets camera,ao --methods edacrt "
        "--repeat 1 --write-rays " +
        path("rays") + " --json " + path("bench.json"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const nlohmann::json json = read_json("bench.json");
    for (const char* set : {"camera-1spp", "ao"}) {
        const std::string rays = path(std::string("rays/cornell_") + set + ".rays");
        ASSERT_TRUE(std::filesystem::exists(rays)) << rays;
        std::uint64_t count = 0;
        for (const nlohmann::json& row : json["results"])
            if (row["set"] == set) count = row["rays"].get<std::uint64_t>();
        EXPECT_GT(count, 0u);
        EXPECT_EQ(std::filesystem::file_size(rays), 32 * count);  // 32-byte ray records
        // `edacrt trace` takes them as they are.
        const auto trace = test::run_cli("trace --scene builtin:cornell --rays " + rays +
                                         " --out " + path("hits") + " -q");
        EXPECT_EQ(trace.exit_code, 0) << trace.output;
        EXPECT_EQ(std::filesystem::file_size(path("hits")), 16 * count);
    }
}

// A sampled tree depends on its draw, so still frame r draws with sampling seed 1 + r: the
// counters are the mean over the frames' draws, each what `edacrt trace` counts with that seed.
TEST_F(BenchCli, EachFrameDrawsItsOwnSampleAndCountersAreTheirMean) {
    const std::string teapot = (test::source_dir() / "assets/teapot/teapot.obj").string();
    const auto result = test::run_cli("bench --scene " + teapot +
                                      " --width 64 --height 64 --spp 1 --sets camera "
                                      "--methods edacrt --threads 1 --repeat 3 --write-rays " +
                                      path("rays") + " --json " + path("bench.json"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const nlohmann::json row = read_json("bench.json")["results"][0];
    const auto rays = row["rays"].get<double>();
    std::set<std::uint64_t> counts;
    double box_sum = 0.0;
    for (int seed = 1; seed <= 3; ++seed) {
        const auto trace = test::run_cli("trace --scene " + teapot + " --rays " +
                                         path("rays/teapot_camera-1spp.rays") + " --out " +
                                         path("hits") + " --threads 1 --sampling-seed " +
                                         std::to_string(seed) + " --stats " + path("stats.json"));
        ASSERT_EQ(trace.exit_code, 0) << trace.output;
        const auto box = read_json("stats.json")["ray_box_tests"].get<std::uint64_t>();
        counts.insert(box);
        box_sum += double(box);
    }
    EXPECT_EQ(counts.size(), 3u) << "the seeds should make three different trees here";
    EXPECT_NEAR(row["box_tests_per_ray"].get<double>(), box_sum / 3.0 / rays, 1e-9);
}

TEST_F(BenchCli, BadParametersFailWithAMessage) {
    const std::string quick = "bench --scene cornell --width 8 --height 8 --repeat 1 ";
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {quick + "--spp 0", "--spp"},
        {quick + "--repeat 0", "--repeat"},
        {quick + "--sets camera,bogus", "unknown ray set 'bogus'"},
        {quick + "--methods edacrt,bogus", "unknown method 'bogus'"},
        {quick + "--width 0", "--width"},
        {"bench --scenes " + path("missing") + " --scene bunny --repeat 1", "not found"},
        {"bench --scene " + path("missing.obj"), "neither a known scene name"},
        {quick + "--json " + path("no-dir/out.json"), "--json"},
        {quick + "--markdown " + path("no-dir/out.md"), "--markdown"},
        {quick + "--write-rays /dev/null/rays", "--write-rays"},
        {quick + "--dynamic --write-rays " + path("rays"), "--write-rays"},
        {"bench --scene cornell --width 16384 --height 16384 --spp 1,4", "choose a smaller"},
        {quick + "--methods edacrt:bins=1", "bins=1: EDACRT parameter bins: '1' is outside"},
        {quick + "--methods edacrt:bins", "'bins' is not KEY=VALUE"},
        {quick + "--methods edacrt:=3", "'=3' is not KEY=VALUE"},
        {quick + "--methods edacrt:", "'' is not KEY=VALUE"},
        {quick + "--methods edacrt:bogus=1", "unknown EDACRT parameter 'bogus'"},
        {quick + "--methods edacrt:presplit=0:preset=paper", "preset must come first"},
        {quick + "--methods edacrt:preset=bogus", "unknown preset 'bogus'"},
        {quick + "--methods dacrt:hit-ratio=sampled", "is what makes dacrt DACRT"},
        {quick + "--methods bvh:max-leaf=0", "max-leaf"},
        {quick + "--methods bvh:c-t=nan", "c-t"},
        {quick + "--methods bvh:leaf=3", "unknown bvh option 'leaf'"},
        {quick + "--methods naive:bins=4", "naive takes no options"},
        {quick + "--dynamic --methods edacrt:bins=4", "--dynamic takes methods only"},
    };
    for (const Case& c : cases) {
        const auto result = test::run_cli(c.args);
        EXPECT_NE(result.exit_code, 0) << c.args << "\n" << result.output;
        EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n"
                                                                    << result.output;
    }
}

TEST_F(BenchCli, RefusesWhatCannotFitInMemory) {
    const auto result =
        test::run_command("EDACRT_MEMORY_LIMIT=1000000 '" + test::cli_path().string() +
                          "' bench --scene cornell --width 512 --height 512 --repeat 1");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("EDACRT_MEMORY_LIMIT"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace edacrt
