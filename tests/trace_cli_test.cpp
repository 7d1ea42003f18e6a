// The edacrt tool: 'trace' equals calling the engine directly; bad input fails cleanly.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "cli_runner.h"
#include "scene/builtin_scenes.h"
#include "test_paths.h"
#include "trace/naive_tracer.h"
#include "trace/ray_file.h"

namespace edacrt {
namespace {

class TraceCli : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ =
            std::filesystem::temp_directory_path() / ("edacrt_cli_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::filesystem::path dir_;
};

std::vector<Ray> random_rays(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> coord(-1.5f, 1.5f);
    std::vector<Ray> rays(count);
    for (Ray& ray : rays) {
        ray.org = {coord(rng), coord(rng), coord(rng)};
        ray.dir = {coord(rng), coord(rng), coord(rng)};
        if (ray.dir == glm::vec3(0.0f)) ray.dir.z = 1.0f;
        if (rng() % 4 == 0) ray.tmax = 0.5f;  // some finite segments
    }
    return rays;
}

TEST_F(TraceCli, HitFileEqualsTheEngine) {
    const std::string spec = "builtin:soup:count=300,seed=4";
    const std::vector<Ray> rays = random_rays(5000, 1);
    write_rays(path("rays.bin"), rays);

    const Scene scene = make_builtin_scene(spec);
    NaiveTracer tracer;
    tracer.set_scene(scene);
    for (const bool any_hit : {false, true}) {
        const auto result =
            test::run_cli("trace --scene " + spec + " --rays " + path("rays.bin") + " --out " +
                          path("hits.bin") + " --method naive" + (any_hit ? " --any-hit" : ""));
        ASSERT_EQ(result.exit_code, 0) << result.output;
        EXPECT_NE(result.output.find("Mrays/s"), std::string::npos) << result.output;

        std::vector<Hit> expected(rays.size());
        tracer.trace(rays, expected, any_hit ? Query::any : Query::closest);
        const std::vector<Hit> got = read_hits(path("hits.bin"));
        ASSERT_EQ(got.size(), expected.size());
        std::size_t hit_count = 0;
        for (std::size_t i = 0; i < got.size(); ++i) {
            ASSERT_EQ(got[i].prim, expected[i].prim) << "ray " << i;
            ASSERT_EQ(got[i].t, expected[i].t) << "ray " << i;
            ASSERT_EQ(got[i].u, expected[i].u) << "ray " << i;
            ASSERT_EQ(got[i].v, expected[i].v) << "ray " << i;
            hit_count += got[i].hit();
        }
        EXPECT_GT(hit_count, 100u);  // the ray set actually exercises hits
        EXPECT_LT(hit_count, rays.size());
    }
}

TEST_F(TraceCli, StatsFileIsWritten) {
    write_rays(path("rays.bin"), random_rays(100, 2));
    const auto result = test::run_cli("trace --scene builtin:sphere:subdiv=2 --rays " +
                                      path("rays.bin") + " --out " + path("hits.bin") +
                                      " --stats " + path("stats.json") + " --threads 1");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    std::ifstream in(path("stats.json"));
    const std::string json((std::istreambuf_iterator<char>(in)), {});
    const auto stats = nlohmann::json::parse(json);
    EXPECT_EQ(stats["rays"], 100);
    EXPECT_EQ(stats["method"], "edacrt");
    // The detailed pass counts exactly what the timed one did.
    EXPECT_EQ(stats["detail"]["per_ray"]["rays"], 100);
    std::uint64_t level_triangle_tests = 0;
    for (const auto& level : stats["detail"]["levels"])
        level_triangle_tests += level["ray_triangle_tests"].get<std::uint64_t>();
    EXPECT_EQ(level_triangle_tests, stats["ray_triangle_tests"].get<std::uint64_t>());
    EXPECT_GT(stats["detail"]["levels"].size(), 0u);
    // Per level, the distribution of the split children's alpha errors; over all levels, the
    // same distribution summed.
    std::uint64_t children = 0;
    double error_sum = 0.0;
    for (const auto& level : stats["detail"]["levels"]) {
        const auto& errors = level["alpha_error"];
        const auto n = errors["children"].get<std::uint64_t>();
        EXPECT_EQ(n, level["alpha_children"].get<std::uint64_t>());
        std::uint64_t binned = 0;
        for (const auto& bin : errors["bins"]) binned += bin.get<std::uint64_t>();
        EXPECT_EQ(binned, n);
        EXPECT_DOUBLE_EQ(errors["mean"].get<double>(), level["alpha_error_mean"].get<double>());
        EXPECT_LE(errors["p50"].get<double>(), errors["p90"].get<double>());
        EXPECT_LE(errors["p90"].get<double>(), errors["max"].get<double>());
        EXPECT_LE(errors["mean"].get<double>(), errors["max"].get<double>());
        std::uint64_t sources = 0;
        for (const auto& source : level["alpha_sources"]) sources += source.get<std::uint64_t>();
        EXPECT_EQ(2 * sources, n);
        EXPECT_NEAR(
            level["samples_per_node_mean"].get<double>() * level["sampled_nodes"].get<double>(),
            level["sampled_rays"].get<double>(), 1e-6);
        children += n;
        error_sum += errors["mean"].get<double>() * double(n);
    }
    const auto& all = stats["detail"]["alpha_error"];
    EXPECT_GT(children, 0u);
    EXPECT_EQ(all["children"].get<std::uint64_t>(), children);
    EXPECT_NEAR(all["mean"].get<double>(), error_sum / double(children), 1e-9);
}

TEST_F(TraceCli, CameraRaysAreTheEnginesAndFeedTrace) {
    const auto result = test::run_cli(
        "camera-rays --scene builtin:cornell --width 32 --height 24 "
        "--out " +
        path("camera.rays"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const std::vector<Ray> rays = read_rays(path("camera.rays"));
    const Scene scene = make_builtin_scene("builtin:cornell");
    const std::vector<Ray> expected = PinholeProjection(*scene.camera, 32, 24).pixel_centre_rays();
    ASSERT_EQ(rays.size(), expected.size());
    EXPECT_EQ(std::memcmp(rays.data(), expected.data(), rays.size() * sizeof(Ray)), 0);

    const auto traced = test::run_cli("trace --scene builtin:cornell --rays " +
                                      path("camera.rays") + " --out " + path("hits.bin"));
    ASSERT_EQ(traced.exit_code, 0) << traced.output;
    const std::vector<Hit> hits = read_hits(path("hits.bin"));
    std::vector<Hit> engine_hits(rays.size());
    const auto tracer = make_tracer(Method::edacrt);
    tracer->set_scene(scene);
    tracer->trace(rays, engine_hits, Query::closest);
    ASSERT_EQ(hits.size(), engine_hits.size());
    EXPECT_EQ(std::memcmp(hits.data(), engine_hits.data(), hits.size() * sizeof(Hit)), 0);
}

TEST_F(TraceCli, BadInputFailsWithAClearMessage) {
    std::ofstream(path("odd.bin"), std::ios::binary) << std::string(40, '\0');
    write_rays(path("one.bin"), random_rays(1, 3));
    const struct {
        std::string args, message;
    } cases[] = {
        {"trace --scene builtin:cornell --rays " + path("odd.bin") + " --out " + path("h.bin"),
         "not a multiple of the 32-byte ray record"},
        {"trace --scene builtin:cornell --rays /no/rays.bin --out " + path("h.bin"),
         "cannot open ray file"},
        {"trace --scene builtin:cornell --rays /dev/zero --out " + path("h.bin"),
         "/dev/zero: not a regular file"},
        {"trace --scene builtin:cornell --rays " + dir_.string() + " --out " + path("h.bin"),
         dir_.string() + ": not a regular file"},
        {"trace --scene /no/scene.obj --rays " + path("one.bin") + " --out " + path("h.bin"),
         "edacrt: error: /no/scene.obj: cannot read OBJ file (no such file)"},
        {"render --scene builtin:nothing --out " + path("x.png"), "unknown built-in scene"},
        {"render --scene builtin:cornell --method magic --out " + path("x.png"),
         "unknown method 'magic'"},
        {"render --scene builtin:cornell --width 0 --out " + path("x.png"), "--width"},
        {"render --scene builtin:cornell --fov 200 --out " + path("x.png"), "field of view"},
        {"render --scene builtin:cornell --eye 1,2 --out " + path("x.png"), "--eye"},
        {"render --scene builtin:cornell --bins 1 --out " + path("x.png"),
         "bins: '1' is outside [2, 256]"},
        {"render --scene builtin:cornell --c-i -1 --out " + path("x.png"), "c-i: '-1' is outside"},
        {"trace --scene builtin:cornell --rays " + path("one.bin") + " --out " + path("h.bin") +
             " --filter-skip sometimes",
         "filter-skip: 'sometimes' is not one of off|paper|triangles"},
        {"trace --scene builtin:cornell --rays " + path("one.bin") + " --out " + path("h.bin") +
             " --far-child always",
         "far-child: 'always' is not one of paper|unstopped"},
        {"trace --scene builtin:cornell --rays " + path("one.bin") + " --out " + path("h.bin") +
             " --preset fast",
         "unknown preset 'fast' (default|paper|dacrt)"},
        {"trace --scene builtin:cornell --rays " + path("one.bin") + " --out " + path("h.bin") +
             " --leaf-rays 2.5",
         "leaf-rays: '2.5' is not an integer"},
        {"trace --scene builtin:cornell --rays " + path("one.bin") + " --out " + path("h.bin") +
             " --method dacrt --hit-ratio sampled",
         "--hit-ratio is what makes dacrt DACRT"},
        {"render --scene builtin:cornell --method dacrt --filter-skip paper --out " + path("x.png"),
         "--filter-skip is what makes dacrt DACRT"},
        {"frobnicate", "unknown command 'frobnicate'"},
    };
    const auto unstopped = test::run_cli("trace --scene builtin:cornell --rays " + path("one.bin") +
                                         " --out " + path("h.bin") + " --far-child unstopped");
    EXPECT_EQ(unstopped.exit_code, 0) << unstopped.output;
    for (const auto& c : cases) {
        const auto result = test::run_cli(c.args);
        EXPECT_NE(result.exit_code, 0) << c.args;
        EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n"
                                                                    << result.output;
    }
}

/// One recursion per batch: the statistics JSON has one node at level 0 and, apart from its
/// timings, is the same for --threads 2 and --threads 4, and for --threads 1 as for
/// `--second-child after-first` on 2 (no task can run beside the first child on one thread);
/// the hit files are identical.
TEST_F(TraceCli, StatisticsAreTheSameForAnyThreadCount) {
    ASSERT_EQ(test::run_cli("camera-rays --scene builtin:sphere:subdiv=5 --width 400 --height 300 "
                            "--out " +
                            path("rays.bin"))
                  .exit_code,
              0);
    const auto strip = [](nlohmann::json j, auto& self) -> nlohmann::json {
        if (j.is_object()) {
            nlohmann::json out = nlohmann::json::object();
            for (auto& [key, value] : j.items())
                if (key.find("seconds") == std::string::npos && key != "mrays_per_second")
                    out[key] = self(value, self);
            return out;
        }
        if (j.is_array())
            for (auto& value : j) value = self(value, self);
        return j;
    };
    for (const std::string preset : {"default", "paper", "dacrt"}) {
        // The same recursion three ways: 2 and 4 threads, and 1 thread against after-first.
        const std::vector<std::pair<std::string, std::string>> runs = {
            {"2", ""}, {"4", ""}, {"1", ""}, {"2", " --second-child after-first"}};
        std::vector<nlohmann::json> stats;
        for (std::size_t r = 0; r < runs.size(); ++r) {
            const std::string n = std::to_string(r);
            const auto result = test::run_cli(
                "trace --scene builtin:sphere:subdiv=5 --rays " + path("rays.bin") + " --out " +
                path("hits" + n + ".bin") + " --stats " + path("stats" + n + ".json") +
                " --preset " + preset + runs[r].second + " --threads " + runs[r].first);
            ASSERT_EQ(result.exit_code, 0) << result.output;
            stats.push_back(nlohmann::json::parse(std::ifstream(path("stats" + n + ".json"))));
        }
        EXPECT_EQ(stats[0]["detail"]["levels"][0]["nodes"], 1) << preset;
        EXPECT_EQ(stats[0]["detail"]["root"]["rays"], 120000) << preset;
        for (const auto& [a, b] : {std::pair{0, 1}, std::pair{2, 3}}) {
            EXPECT_EQ(strip(stats[a], strip), strip(stats[b], strip)) << preset << ", run " << b;
            EXPECT_EQ(test::run_command("cmp " + path("hits" + std::to_string(a) + ".bin") + " " +
                                        path("hits" + std::to_string(b) + ".bin"))
                          .exit_code,
                      0)
                << preset << ", run " << b;
        }
    }
}

TEST_F(TraceCli, WriteErrorsFailTheCommand) {
    // /dev/full takes the open and fails the writes; small outputs fail only at the close.
    write_rays(path("rays.bin"), random_rays(10, 5));
    const struct {
        std::string args, message;
    } cases[] = {
        {"trace --scene builtin:cornell --rays " + path("rays.bin") + " --out /dev/full",
         "/dev/full: cannot write hit file (No space left on device)"},
        {"trace --scene builtin:cornell --rays " + path("rays.bin") + " --out " + path("h.bin") +
             " --stats /dev/full",
         "/dev/full: cannot write statistics (No space left on device)"},
        {"camera-rays --scene builtin:cornell --width 4 --height 4 --out /dev/full",
         "/dev/full: cannot write ray file (No space left on device)"},
    };
    for (const auto& c : cases) {
        const auto result = test::run_cli(c.args);
        EXPECT_EQ(result.exit_code, 1) << c.args << "\n" << result.output;
        EXPECT_NE(result.output.find("edacrt: error: " + c.message), std::string::npos)
            << c.args << "\n"
            << result.output;
    }
}

TEST_F(TraceCli, HelpExplainsTheCommands) {
    const auto result = test::run_cli("--help");
    EXPECT_EQ(result.exit_code, 0);
    EXPECT_NE(result.output.find("render"), std::string::npos);
    EXPECT_NE(result.output.find("trace"), std::string::npos);
    const auto trace_help = test::run_cli("trace --help");
    EXPECT_NE(trace_help.output.find("ox oy oz dx dy dz tmin tmax"), std::string::npos);
}

}  // namespace
}  // namespace edacrt
