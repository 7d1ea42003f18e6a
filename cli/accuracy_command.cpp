// edacrt accuracy: how often each method's hits differ from a double-precision reference, and
// how fast it traced them, on several ray sets (the hit-accuracy table of bench/README.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <random>
#include <span>
#include <sstream>

#include "commands.h"
#include "common_options.h"
#include "enum_flags.h"
#include "progress.h"
#include "render/bsdf.h"
#include "render/camera_options.h"
#include "render/shading_scene.h"
#include "trace/reference_hits.h"
#include "util/error.h"

namespace edacrt::cli {
namespace {

struct AccuracyOptions {
    CommonOptions common;
    std::vector<std::string> methods = enum_name_list(kMethods);
    int rays = 20000;
    std::uint32_t seed = 1;
    int repeats = 3;
    bool skip_naive = false;
};

// How long a sample must take to time the brute-force passes up front, and the estimate worth
// announcing.
constexpr double kEstimateSeconds = 0.25;
constexpr double kAnnounceSeconds = 10.0;

using RaySet = std::pair<std::string, std::vector<Ray>>;

/// Camera rays, rays from random points inside the box, rays spawned from surfaces the way
/// the renderer spawns them (some at grazing angles), axis-parallel rays.
std::vector<RaySet> make_ray_sets(const Scene& scene, const Camera& camera, int count,
                                  std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const Aabb box = scene.bounds();
    const auto inside = [&] {
        return box.lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * (box.hi - box.lo);
    };
    const auto direction = [&] {
        glm::vec3 d;
        do d = glm::vec3(unit(rng), unit(rng), unit(rng)) * 2.0f - 1.0f;
        while (glm::dot(d, d) > 1.0f || glm::dot(d, d) < 1e-4f);
        return glm::normalize(d);
    };
    const auto surface = [&] {
        const auto prim = std::int32_t(rng() % scene.triangle_count());
        const float a = unit(rng), b = unit(rng) * (1.0f - a);
        const Triangle tri = scene.corners(std::size_t(prim));
        const glm::vec3 n = unit_normal(tri);
        const glm::vec3 p = (1 - a - b) * tri.p0 + a * tri.p1 + b * tri.p2;
        return make_surface(scene, Ray{p + n, -n}, Hit{1.0f, prim, a, b});
    };
    std::vector<RaySet> sets(5);
    const int side = std::max(1, int(std::sqrt(double(count))));
    const PinholeProjection projection(camera, side, side);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            sets[0].second.push_back(projection.ray(float(x) + unit(rng), float(y) + unit(rng)));
    sets[0].first = "camera";
    sets[1].first = "random inside";
    sets[2].first = "from surfaces";
    sets[3].first = "grazing from surfaces";
    sets[4].first = "axis-parallel";
    for (int i = 0; i < count; ++i) {
        sets[1].second.push_back({inside(), direction()});
        const Surface s = surface();
        sets[2].second.push_back(
            spawn_ray(s, sample_cosine_hemisphere(s.ng, {unit(rng), unit(rng)})));
        glm::vec3 t, b;
        orthonormal_basis(s.ng, t, b);
        const float angle = std::pow(10.0f, -1.0f - 5.0f * unit(rng));  // 1e-6 .. 1e-1 rad
        const float phi = 6.2831853f * unit(rng);
        sets[3].second.push_back(
            spawn_ray(s, glm::normalize(std::cos(phi) * t + std::sin(phi) * b + angle * s.ng)));
        glm::vec3 d(0.0f);
        d[int(rng() % 3)] = rng() % 2 ? 1.0f : -1.0f;
        sets[4].second.push_back({inside(), d});
    }
    return sets;
}

struct Accuracy {
    double seconds = 0.0;  // median of the repeats
    std::size_t hit_mismatch = 0, triangle_mismatch = 0, both_hit = 0;
    double max_relative_t_error = 0.0, sum_relative_t_error = 0.0;
};

/// Times `repeats` traces of the set (calling `traced` after each), then compares the hits.
Accuracy measure(Tracer& tracer, std::span<const Triangle> triangles, const RaySet& set,
                 const std::vector<ReferenceHit>& reference, int repeats,
                 const std::function<void()>& traced) {
    const std::vector<Ray>& rays = set.second;
    std::vector<Hit> hits(rays.size());
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
        const auto start = std::chrono::steady_clock::now();
        tracer.trace(rays, hits, Query::closest);
        times.push_back(seconds_since(start));
        traced();
    }
    std::sort(times.begin(), times.end());
    Accuracy a;
    a.seconds = times[times.size() / 2];
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const ReferenceHit& ref = reference[i];
        if (hits[i].hit() != (ref.prim >= 0)) {
            ++a.hit_mismatch;
            continue;
        }
        if (!hits[i].hit()) continue;
        if (hits[i].prim != ref.prim) {
            // Not a tie: the reported triangle is hit farther away than the reference's.
            const auto t = intersect_double(rays[i], triangles[std::size_t(hits[i].prim)]);
            if (!t || std::abs(*t - ref.t) > 1e-7 * ref.t) {
                ++a.triangle_mismatch;
                continue;  // a different hit: its t is not an error of the same hit's t
            }
        }
        ++a.both_hit;
        const double error = std::abs(double(hits[i].t) - ref.t) / ref.t;
        a.max_relative_t_error = std::max(a.max_relative_t_error, error);
        a.sum_relative_t_error += error;
    }
    return a;
}

/// Seconds the brute-force passes will take: the reference's one pass and naive's `repeats`
/// (0 when naive is not measured), extrapolated from timing both on a sample of the rays.
struct BruteForceEstimate {
    double reference = 0.0, naive = 0.0;
};

/// Seconds `pass` would take on all of `rays`: timed on 64, 256, ... of them (spread over the
/// sets) until one sample takes long enough to be measured well.
double extrapolate(const std::vector<Ray>& rays,
                   const std::function<void(std::span<const Ray>)>& pass) {
    for (std::size_t n = 64;; n *= 4) {
        const std::size_t stride = std::max<std::size_t>(1, rays.size() / n);
        std::vector<Ray> sample;
        for (std::size_t i = 0; i < rays.size(); i += stride) sample.push_back(rays[i]);
        const auto start = std::chrono::steady_clock::now();
        pass(sample);
        const double seconds = seconds_since(start);
        if (seconds >= kEstimateSeconds || stride == 1)
            return seconds * double(rays.size()) / double(sample.size());
    }
}

BruteForceEstimate estimate_brute_force(const Scene& scene, std::span<const Triangle> triangles,
                                        const std::vector<RaySet>& sets, bool naive, int repeats) {
    std::vector<Ray> rays;
    for (const RaySet& set : sets) rays.insert(rays.end(), set.second.begin(), set.second.end());
    BruteForceEstimate estimate;
    estimate.reference =
        extrapolate(rays, [&](std::span<const Ray> sample) { reference_hits(triangles, sample); });
    if (naive) {
        const auto tracer = make_tracer(Method::naive);
        tracer->set_scene(scene);
        estimate.naive = repeats * extrapolate(rays, [&](std::span<const Ray> sample) {
                             std::vector<Hit> hits(sample.size());
                             tracer->trace(sample, hits, Query::closest);
                         });
    }
    return estimate;
}

/// The reference hits of every set, a slice at a time so that progress can show.
std::vector<std::vector<ReferenceHit>> compute_references(std::span<const Triangle> triangles,
                                                          const std::vector<RaySet>& sets,
                                                          Progress& progress) {
    std::size_t total = 0, done = 0;
    for (const RaySet& set : sets) total += set.second.size();
    std::vector<std::vector<ReferenceHit>> references;
    for (const RaySet& set : sets) {
        const std::span<const Ray> rays = set.second;
        std::vector<ReferenceHit>& hits = references.emplace_back();
        const std::size_t slice = std::max<std::size_t>(1024, rays.size() / 16);
        for (std::size_t begin = 0; begin < rays.size(); begin += slice) {
            const auto part = reference_hits(
                triangles, rays.subspan(begin, std::min(slice, rays.size() - begin)));
            hits.insert(hits.end(), part.begin(), part.end());
            done += part.size();
            progress.update(double(done) / double(total), double(done), set.first);
        }
        progress.step(double(done) / double(total), double(done), set.first + " done");
    }
    return references;
}

void run(const AccuracyOptions& o) {
    const auto threads = apply_thread_limit(o.common);
    std::vector<std::string> methods = o.methods;
    check_flags([&] {
        if (o.rays < 1 || o.rays > 10'000'000) throw InputError("--rays must be 1..10000000");
        if (o.skip_naive) std::erase(methods, std::string(enum_name(kMethods, Method::naive)));
        if (methods.empty())
            throw InputError("no method left to measure (--skip-naive removed naive)");
        for (const std::string& name : methods) parse_enum_or_throw(kMethods, name);
    });
    const std::vector<NamedPath> outputs = {{"--stats", o.common.stats_path}};
    check_distinct_files(outputs, {{"--scene", o.common.scene}});
    const Scene scene = load_scene_verbose(o.common.scene);
    check_outputs_spare_scene(outputs, scene);
    if (scene.triangle_count() == 0) throw InputError(scene.source + ": no triangles");
    const Camera camera = choose_camera(scene, CameraOptions{});
    const FrameVector<Triangle> triangles = gather_triangles(scene);
    const std::vector<RaySet> sets = make_ray_sets(scene, camera, o.rays, o.seed);
    const ProgressStyle style = progress_style(o.common.quiet);

    const bool naive = std::find(methods.begin(), methods.end(), "naive") != methods.end();
    const BruteForceEstimate estimate =
        estimate_brute_force(scene, triangles, sets, naive, o.repeats);
    if (style != ProgressStyle::quiet && estimate.reference + estimate.naive >= kAnnounceSeconds) {
        const std::string reference = "the double-precision brute-force reference";
        std::cerr << "accuracy: estimated " << format_duration(estimate.reference) << " for "
                  << reference;
        if (naive)
            std::cerr << " and " << format_duration(estimate.naive) << " for naive (" << o.repeats
                      << (o.repeats == 1 ? " timed run" : " timed runs")
                      << "); --skip-naive leaves naive out, the hits are still compared with "
                      << reference << "\n";
        else if (o.skip_naive)
            std::cerr << "; naive is skipped (--skip-naive), every method is still compared "
                         "with that reference\n";
        else
            std::cerr << "\n";
    }
    std::vector<std::vector<ReferenceHit>> references;
    {
        Progress progress(style, "reference", Progress::Unit::rays);
        progress.expect_seconds(estimate.reference);
        progress.begin(sets.front().first);
        references = compute_references(triangles, sets, progress);
    }

    nlohmann::json results = nlohmann::json::array();
    std::cout << std::left << std::setw(8) << "method" << std::setw(24) << "ray set" << std::right
              << std::setw(10) << "Mrays/s" << std::setw(12) << "hit diff" << std::setw(12)
              << "tri diff" << std::setw(12) << "max rel t" << std::setw(12) << "mean rel t"
              << std::endl;
    std::size_t set_rays = 0;
    for (const RaySet& set : sets) set_rays += set.second.size();
    const double method_rays = double(set_rays) * o.repeats;
    for (const std::string& name : methods) {
        CommonOptions common = o.common;
        common.method = parse_enum_or_throw(kMethods, name);
        const auto tracer = make_tracer(common);
        Progress progress(style, name, Progress::Unit::rays);
        if (name == "naive") progress.expect_seconds(estimate.naive);
        progress.begin("set_scene");
        tracer->set_scene(scene);
        double traced = 0.0;
        for (std::size_t s = 0; s < sets.size(); ++s) {
            const auto label = [&](int run) {
                return sets[s].first + ", run " + std::to_string(run) + "/" +
                       std::to_string(o.repeats);
            };
            int run = 1;
            progress.begin(label(run));
            const Accuracy a = measure(*tracer, triangles, sets[s], references[s], o.repeats, [&] {
                traced += double(sets[s].second.size());
                progress.step(traced / method_rays, traced, label(run) + " done");
                if (run < o.repeats) progress.begin(label(++run));
            });
            const double n = double(sets[s].second.size());
            const double mrays = n / a.seconds * 1e-6;
            const double mean_error = a.both_hit ? a.sum_relative_t_error / double(a.both_hit) : 0;
            std::ostringstream row;
            row << std::left << std::setw(8) << name << std::setw(24) << sets[s].first << std::right
                << std::setw(10) << std::setprecision(3) << mrays << std::setw(12)
                << double(a.hit_mismatch) / n << std::setw(12) << double(a.triangle_mismatch) / n
                << std::setw(12) << a.max_relative_t_error << std::setw(12) << mean_error;
            progress.print(std::cout, row.str());
            results.push_back({{"method", name},
                               {"ray_set", sets[s].first},
                               {"rays", sets[s].second.size()},
                               {"seconds", a.seconds},
                               {"mrays_per_second", mrays},
                               {"hit_mismatch_fraction", double(a.hit_mismatch) / n},
                               {"triangle_mismatch_fraction", double(a.triangle_mismatch) / n},
                               {"max_relative_t_error", a.max_relative_t_error},
                               {"mean_relative_t_error", mean_error}});
        }
    }
    write_stats(o.common, {{"command", "accuracy"},
                           {"scene", scene.source},
                           {"triangles", scene.triangle_count()},
                           {"reference", "double-precision Moller-Trumbore, brute force"},
                           {"skipped_naive", o.skip_naive},
                           {"results", results}});
}

}  // namespace

std::function<void()> add_accuracy_command(CLI::App& app) {
    auto options = std::make_shared<AccuracyOptions>();
    AccuracyOptions& o = *options;
    CLI::App* command = app.add_subcommand(
        "accuracy",
        "Compare every method's closest hits with a double-precision brute-force reference on "
        "camera, random, surface, grazing and axis-parallel rays, and time them.\n"
        "Example: edacrt accuracy --scene assets/spot/spot.obj --stats out/accuracy.json");
    add_common_options(*command, o.common);
    command
        ->add_option("--methods", o.methods,
                     flags::enum_option_help("methods to measure", kMethods))
        ->delimiter(',');
    command->add_flag("--skip-naive", o.skip_naive,
                      "leave naive out: its brute force takes most of the time on large scenes "
                      "(the estimate is printed up front); the hits are still compared with the "
                      "double-precision brute-force reference");
    command->add_option("--rays", o.rays, "rays per set")->capture_default_str();
    command->add_option("--seed", o.seed, "seed of the ray sets")->capture_default_str();
    command->add_option("--repeats", o.repeats, "timed runs per set (median)")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    return [options] { run(*options); };
}

}  // namespace edacrt::cli
