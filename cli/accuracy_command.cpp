// edacrt accuracy: how often each method's hits differ from a double-precision reference, and
// how fast it traced them, on several ray sets (the hit-accuracy table of bench/README.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>

#include "camera_options.h"
#include "commands.h"
#include "common_options.h"
#include "render/bsdf.h"
#include "render/shading_scene.h"
#include "trace/reference_hits.h"
#include "util/error.h"

namespace edacrt::cli {
namespace {

struct AccuracyOptions {
    CommonOptions common;
    std::vector<std::string> methods = method_names();
    int rays = 20000;
    std::uint32_t seed = 1;
    int repeats = 3;
};

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

Accuracy measure(Tracer& tracer, const std::vector<Triangle>& triangles, const RaySet& set,
                 const std::vector<ReferenceHit>& reference, int repeats) {
    const std::vector<Ray>& rays = set.second;
    std::vector<Hit> hits(rays.size());
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
        const auto start = std::chrono::steady_clock::now();
        tracer.trace(rays, hits, Query::closest);
        times.push_back(seconds_since(start));
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

void run(const AccuracyOptions& o) {
    const auto threads = apply_thread_limit(o.common);
    if (o.rays < 1 || o.rays > 10'000'000) throw InputError("--rays must be 1..10000000");
    const Scene scene = load_scene_verbose(o.common.scene);
    if (scene.triangle_count() == 0) throw InputError(scene.source + ": no triangles");
    const Camera camera = choose_camera(scene, CameraOptions{});
    const std::vector<Triangle> triangles = gather_triangles(scene);
    const std::vector<RaySet> sets = make_ray_sets(scene, camera, o.rays, o.seed);
    std::vector<std::vector<ReferenceHit>> references;
    for (const RaySet& set : sets) references.push_back(reference_hits(triangles, set.second));

    nlohmann::json results = nlohmann::json::array();
    std::cout << std::left << std::setw(8) << "method" << std::setw(24) << "ray set" << std::right
              << std::setw(10) << "Mrays/s" << std::setw(12) << "hit diff" << std::setw(12)
              << "tri diff" << std::setw(12) << "max rel t" << std::setw(12) << "mean rel t"
              << "\n";
    for (const std::string& name : o.methods) {
        CommonOptions common = o.common;
        common.method = name;
        const auto tracer = make_tracer(common);
        tracer->set_scene(scene);
        for (std::size_t s = 0; s < sets.size(); ++s) {
            const Accuracy a = measure(*tracer, triangles, sets[s], references[s], o.repeats);
            const double n = double(sets[s].second.size());
            const double mrays = n / a.seconds * 1e-6;
            const double mean_error = a.both_hit ? a.sum_relative_t_error / double(a.both_hit) : 0;
            std::cout << std::left << std::setw(8) << name << std::setw(24) << sets[s].first
                      << std::right << std::setw(10) << std::setprecision(3) << mrays
                      << std::setw(12) << double(a.hit_mismatch) / n << std::setw(12)
                      << double(a.triangle_mismatch) / n << std::setw(12) << a.max_relative_t_error
                      << std::setw(12) << mean_error << "\n";
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
    command->add_option("--methods", o.methods, "methods to measure")->delimiter(',');
    command->add_option("--rays", o.rays, "rays per set")->capture_default_str();
    command->add_option("--seed", o.seed, "seed of the ray sets")->capture_default_str();
    command->add_option("--repeats", o.repeats, "timed runs per set (median)")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    return [options] { run(*options); };
}

}  // namespace edacrt::cli
