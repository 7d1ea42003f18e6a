// edacrt bench --dynamic: divide-and-conquer ray tracing keeps no structure, so geometry that
// changes every frame costs it nothing extra, while a BVH must be rebuilt or refitted (Mora
// 2011, Afra 2012). Every method follows the same animation frame by frame, its structure kept
// between frames as update_scene() allows; each frame is timed as update + trace, methods
// interleaved (the first to go rotates), medians over the frames; the hits are compared on
// every frame.
#include "bench_dynamic.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <stdexcept>

#include "bench_report.h"
#include "bench_scenes.h"
#include "common_options.h"
#include "dynamic_report.h"
#include "render/benchmark_rays.h"
#include "render/render_memory.h"
#include "scene/animation.h"
#include "scene/scene_paths.h"
#include "util/error.h"
#include "util/output_file.h"

namespace edacrt::cli {
namespace {

struct Variant {
    std::string label;
    Method method;
    SceneUpdate how;
    EdacrtParams params = {};
};

/// Each method once; the BVH and Embree in each of their ways to take a frame, and EDACRT also
/// without pre-split pieces, whose clipping is most of its per-frame work on large triangles.
std::vector<Variant> make_variants(const std::vector<std::string>& names) {
    std::vector<Variant> variants;
    for (const std::string& name : names) {
        const Method method = parse_enum_or_throw(kMethods, name);
        if (std::any_of(variants.begin(), variants.end(),
                        [&](const Variant& v) { return v.method == method; }))
            continue;
        switch (method) {
            case Method::bvh:
                variants.push_back({"bvh/rebuild", method, SceneUpdate::rebuild});
                variants.push_back({"bvh/refit", method, SceneUpdate::refit});
                break;
            case Method::embree:
                make_tracer(Method::embree);  // throws when this build has no Embree
                for (SceneUpdate how :
                     {SceneUpdate::rebuild, SceneUpdate::dynamic, SceneUpdate::refit})
                    variants.push_back(
                        {"embree/" + std::string(enum_name(kSceneUpdates, how)), method, how});
                break;
            case Method::edacrt: {
                variants.push_back({name, method, SceneUpdate::rebuild});
                EdacrtParams no_pieces;
                no_pieces.presplit = 0.0f;
                variants.push_back({"edacrt/presplit-0", method, SceneUpdate::rebuild, no_pieces});
                break;
            }
            default:
                variants.push_back({name, method, SceneUpdate::rebuild});
        }
    }
    return variants;
}

/// The methods' hits are compared with the first of our kernel, else the first.
std::size_t reference_index(const std::vector<Variant>& variants) {
    for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i].method != Method::embree) return i;
    return 0;
}

void add(Agreement& total, const Agreement& frame) {
    if (total.first_disagreement < 0) total.first_disagreement = frame.first_disagreement;
    total.rays += frame.rays;
    total.ties += frame.ties;
    total.tolerated += frame.tolerated;
    total.disagreements += frame.disagreements;
}

/// Times every variant over `frames` frames of the animation on `rays` (closest hits). The
/// tracers first take the frame at t = 0, untimed: the structure a previous frame left; frame
/// f of the timed ones is at t = duration * f / (frames + 1).
DynamicSetRun run_set(AnimatedScene& animated, const std::vector<Variant>& variants,
                      const std::string& scene_name, const std::string& set_name, int spp,
                      const std::vector<Ray>& rays, int frames, int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    std::size_t(threads));
    Scene& scene = animated.scene;
    Animation& animation = *animated.animation;
    DynamicSetRun run{scene_name, set_name, rays.size(), scene.triangle_count(), spp, {}, {}};
    std::vector<std::unique_ptr<Tracer>> tracers;
    animation.frame(0.0, scene);
    for (const Variant& v : variants) {
        tracers.push_back(make_tracer(v.method, v.params, kDefaultEmbreeMode));
        tracers.back()->update_scene(scene, v.how);
        run.methods.push_back({v.label, v.method, v.how, UpdateWork::none, {}, {}, {}, false});
    }
    const std::size_t ref = reference_index(variants);
    run.methods[ref].reference = true;
    std::vector<std::vector<Hit>> hits(variants.size(), std::vector<Hit>(rays.size()));
    FrameVector<Triangle> triangles;
    for (int f = 1; f <= frames; ++f) {
        auto start = std::chrono::steady_clock::now();
        animation.frame(animation.duration() * f / (frames + 1), scene);
        run.animate_seconds.push_back(seconds_since(start));
        for (std::size_t k = 0; k < variants.size(); ++k) {
            const std::size_t i = (k + std::size_t(f)) % variants.size();
            DynamicMethodRun& m = run.methods[i];
            const UpdateStats update = tracers[i]->update_scene(scene, variants[i].how);
            m.work = update.work;
            m.update_seconds.push_back(update.seconds);
            start = std::chrono::steady_clock::now();
            tracers[i]->trace(rays, hits[i], Query::closest);
            m.trace_seconds.push_back(seconds_since(start));
        }
        gather_triangles(scene, triangles);
        for (std::size_t i = 0; i < variants.size(); ++i)
            if (i != ref)
                add(run.methods[i].agreement,
                    compare_hits(triangles, rays, hits[ref], hits[i], Query::closest,
                                 variants[i].method != Method::embree &&
                                     variants[ref].method != Method::embree));
    }
    return run;
}

void validate(const DynamicBenchOptions& o) {
    if (o.frames < 1 || o.frames > 1000) throw InputError("--frames must be from 1 to 1000");
    for (const double r : o.rays_per_triangle)
        if (!(r > 0.0 && r <= 1e4))
            throw InputError("--rays-per-triangle values must be in (0, 10000]");
    if (o.spp.empty() && o.rays_per_triangle.empty())
        throw InputError("nothing to measure: give --spp or --rays-per-triangle");
}

/// Refuses a set that cannot fit: its rays, and per variant a hit buffer and a tracer's per-ray
/// state.
void check_memory(std::uint64_t rays, std::size_t variants) {
    const std::uint64_t need = rays * (sizeof(Ray) + variants * trace_bytes_per_ray());
    const MemoryLimit limit = memory_limit();
    if (rays > std::uint64_t(1) << 31 || need > limit.bytes)
        throw InputError("a set of " + std::to_string(rays) + " rays needs about " +
                         std::to_string(need / 1'000'000) + " MB with " + std::to_string(variants) +
                         " tracers, more than the " + std::to_string(limit.bytes / 1'000'000) +
                         " MB of " + limit.source + "; choose fewer rays");
}

/// The 1-spp camera rays of an image of about `count` pixels, as square as whole pixels allow.
std::vector<Ray> sweep_rays(const Camera& camera, double count, std::uint32_t seed) {
    const int width = std::max(1, int(std::lround(std::sqrt(count))));
    const int height = std::max(1, int(std::lround(count / width)));
    return jittered_camera_rays(PinholeProjection(camera, width, height), width, height, 1, seed);
}

}  // namespace

void run_dynamic_bench(const DynamicBenchOptions& o) {
    validate(o);
    const std::vector<Variant> variants = make_variants(o.methods);
    check_writable(o.json_path, "--json");
    check_writable(o.markdown_path, "--markdown");
    std::vector<BenchScene> scenes;
    if (animation_has_geometry(o.animation)) {
        if (!o.scenes.empty())
            throw InputError("the animation " + o.animation +
                             " names its own geometry: "
                             "give no --scene with it");
        scenes.push_back({std::filesystem::path(o.animation).stem().string(), ""});
    } else {
        scenes = resolve_bench_scenes(
            o.scenes.empty() ? std::vector<std::string>{"bunny", "sponza"} : o.scenes,
            o.scenes_dir.empty() ? default_scenes_dir(EDACRT_SOURCE_DIR) : o.scenes_dir,
            o.scenes_dir_required);
    }
    if (scenes.empty()) throw InputError("no scene to measure (all were skipped)");
    const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();

    nlohmann::json scenes_json = nlohmann::json::array(), rows_json = nlohmann::json::array();
    std::vector<DynamicSetRun> runs;
    runs.reserve(scenes.size() * (o.spp.size() + o.rays_per_triangle.size()));  // rows point in
    std::vector<DynamicRow> camera_rows;
    std::uint64_t disagreements = 0;
    std::cout << dynamic_table_header();
    for (const BenchScene& bench_scene : scenes) {
        AnimatedScene animated = load_animated_scene(bench_scene.spec, o.animation);
        const std::size_t triangles = animated.scene.triangle_count();
        if (triangles == 0) throw InputError(animated.scene.source + ": no triangles");
        const BenchView view = bench_view(animated.scene, bench_scene.name);
        std::cerr << "bench: " << bench_scene.name << ": " << triangles << " triangles animated by "
                  << animated.animation->spec() << ", " << (view.inside ? "inside" : "outside")
                  << " view, " << view.reason << "\n";
        scenes_json.push_back({{"name", bench_scene.name},
                               {"source", animated.scene.source},
                               {"triangles", triangles},
                               {"animation", animated.animation->spec()},
                               {"duration_seconds", animated.animation->duration()},
                               {"view_inside", view.inside}});
        struct Set {
            std::string name;
            int spp;
            std::vector<Ray> rays;
        };
        std::vector<Set> sets;
        const PinholeProjection projection(view.camera, o.width, o.height);
        for (const int spp : o.spp) {
            check_memory(std::uint64_t(o.width) * std::uint64_t(o.height) * std::uint64_t(spp),
                         variants.size());
            sets.push_back({"camera-" + std::to_string(spp) + "spp", spp,
                            jittered_camera_rays(projection, o.width, o.height, spp, o.seed)});
        }
        for (const double r : o.rays_per_triangle) {
            check_memory(std::uint64_t(r * double(triangles)) + 1, variants.size());
            sets.push_back({"sweep", 1, sweep_rays(view.camera, r * double(triangles), o.seed)});
        }
        for (Set& set : sets) {
            std::cerr << "bench: " << bench_scene.name << " " << set.name << ", " << set.rays.size()
                      << " rays, " << o.frames << " frames, " << threads << " thread(s)\n";
            runs.push_back(run_set(animated, variants, bench_scene.name, set.name, set.spp,
                                   set.rays, o.frames, threads));
            set.rays = {};
            for (const DynamicRow& row : dynamic_rows(runs.back())) {
                rows_json.push_back(dynamic_row_json(row));
                if (!runs.back().sweep()) camera_rows.push_back(row);
                std::cout << dynamic_table_row(row) << std::flush;
                if (row.method->agreement.disagreements) {
                    disagreements += row.method->agreement.disagreements;
                    std::cerr << "bench: DISAGREEMENT: " << row.method->label << " differs from "
                              << "the reference on " << row.method->agreement.disagreements
                              << " rays of " << row.run->scene << " " << row.run->set
                              << " (first: ray " << row.method->agreement.first_disagreement
                              << ")\n";
                }
            }
        }
    }

    const std::vector<Crossover> found = crossovers(runs);
    nlohmann::json crossovers_json = nlohmann::json::array();
    if (!found.empty()) std::cout << "\n" << crossover_markdown_table(found);
    for (const Crossover& c : found) crossovers_json.push_back(crossover_json(c));
    const nlohmann::json machine = machine_json();
    if (!o.json_path.empty())
        write_file(o.json_path,
                   nlohmann::json{{"command", "bench --dynamic"},
                                  {"machine", machine},
                                  {"settings",
                                   {{"animation", o.animation},
                                    {"frames", o.frames},
                                    {"spp", o.spp},
                                    {"rays_per_triangle", o.rays_per_triangle},
                                    {"width", o.width},
                                    {"height", o.height},
                                    {"threads", threads},
                                    {"seed", o.seed},
                                    {"methods", o.methods},
                                    {"embree_mode", enum_name(kEmbreeModes, kDefaultEmbreeMode)},
                                    {"edacrt_params", "default preset"}}},
                                  {"scenes", scenes_json},
                                  {"results", rows_json},
                                  {"crossovers", crossovers_json},
                                  {"agreement_ok", disagreements == 0}}
                           .dump(2) +
                       "\n",
                   "benchmark JSON");
    if (!o.markdown_path.empty())
        write_file(o.markdown_path,
                   "`edacrt bench --dynamic`, " + o.animation + ", " + std::to_string(o.frames) +
                       " frames per set (medians), " + std::to_string(threads) + " thread(s); " +
                       machine["cpu"].get<std::string>() + ", " +
                       machine["date"].get<std::string>() + ", revision " +
                       machine["git_revision"].get<std::string>() + ".\n\n" +
                       dynamic_markdown_table(camera_rows) + "\n" + crossover_markdown_table(found),
                   "benchmark markdown");
    if (disagreements)
        throw std::runtime_error("the methods disagree on " + std::to_string(disagreements) +
                                 " rays (see DISAGREEMENT above)");
}

}  // namespace edacrt::cli
