// edacrt bench: every method on the same rays in one process, frame by frame (set_scene() and
// trace(), nothing kept between frames), repetitions interleaved across methods; a table, JSON
// and markdown, and a check that all methods found the same hits.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <iostream>
#include <numeric>
#include <random>
#include <stdexcept>

#include "bench_dynamic.h"
#include "bench_rays.h"
#include "bench_report.h"
#include "bench_scenes.h"
#include "commands.h"
#include "common_options.h"
#include "enum_flags.h"
#include "progress.h"
#include "render/render_memory.h"
#include "scene/scene_paths.h"
#include "trace/ray_file.h"
#include "util/error.h"
#include "util/output_file.h"

namespace edacrt::cli {
namespace {

struct BenchOptions {
    std::string scenes_dir;
    std::vector<std::string> scenes;
    std::vector<std::string> sets = enum_name_list(kRaySetKinds);
    std::vector<int> spp = {1, 4, 16};
    std::vector<std::string> methods = {"edacrt", "dacrt", "bvh", "embree"};
    int width = 1024, height = 1024;
    int repeat = 5;
    int threads = 0;
    bool thread_sweep = false;
    bool quiet = false;
    std::uint32_t seed = 1;
    std::string json_path, markdown_path;
    std::string rays_dir;  // --write-rays
    // --dynamic (bench_dynamic.h): the frames of an animation instead of still frames.
    bool dynamic = false;
    DynamicBenchOptions animation;
};

/// A tracer to time: a method, and for Embree one of its modes.
struct Variant {
    std::string label;
    Method method;
    EmbreeMode mode = kDefaultEmbreeMode;
};

std::vector<Variant> make_variants(const std::vector<std::string>& names) {
    std::vector<Variant> variants;
    for (const std::string& name : names) {
        const Method method = parse_enum_or_throw(kMethods, name);
        if (std::any_of(variants.begin(), variants.end(),
                        [&](const Variant& v) { return v.method == method; }))
            continue;
        if (method == Method::naive)
            std::cerr << "bench: warning: naive tests every ray against every triangle; expect "
                         "hours on large scenes\n";
        if (method != Method::embree) {
            variants.push_back({name, method});
            continue;
        }
        make_tracer(Method::embree);  // throws when this build has no Embree
        for (EmbreeMode mode : {EmbreeMode::packet8, EmbreeMode::single, EmbreeMode::stream})
            variants.push_back(
                {"embree/" + std::string(enum_name(kEmbreeModes, mode)), method, mode});
    }
    return variants;
}

/// The ray sets to run, by name ("camera-4spp", ...), in order.
struct SetChoice {
    std::string name;
    RaySetKind kind;
    int spp = 1;
};

std::vector<SetChoice> make_set_choices(const BenchOptions& o) {
    std::vector<SetChoice> sets;
    for (const std::string& name : o.sets) {
        const RaySetKind kind = parse_enum_or_throw(kRaySetKinds, name);
        if (kind != RaySetKind::camera) {
            sets.push_back({name, kind});
            continue;
        }
        for (int spp : o.spp) sets.push_back({"camera-" + std::to_string(spp) + "spp", kind, spp});
    }
    return sets;
}

std::vector<Ray> make_rays(const BenchRays& rays, const SetChoice& set) {
    switch (set.kind) {
        case RaySetKind::camera:
            return rays.camera(set.spp);
        case RaySetKind::diffuse:
            return rays.diffuse();
        case RaySetKind::ao:
            return rays.ambient_occlusion();
        case RaySetKind::shadow:
            return rays.shadow();
    }
    return {};
}

/// Refuses a run whose largest ray set cannot fit (render_memory.h): the rays, one hit buffer
/// per variant, the tracers' per-ray state and the 1-spp camera rays and hits kept for the
/// secondary sets. Scenes come on top.
void check_memory(const BenchOptions& o, std::size_t variants) {
    const std::uint64_t pixels = std::uint64_t(o.width) * std::uint64_t(o.height);
    const std::uint64_t rays =
        pixels * std::uint64_t(*std::max_element(o.spp.begin(), o.spp.end()));
    if (rays > std::uint64_t(1) << 31)
        throw InputError("--width x --height x spp gives " + std::to_string(rays) +
                         " rays in a set; at most 2^31 are supported");
    const std::uint64_t need = rays * (trace_bytes_per_ray() + (variants - 1) * sizeof(Hit)) +
                               pixels * (sizeof(Ray) + sizeof(Hit));
    const MemoryLimit limit = memory_limit();
    if (need > limit.bytes)
        throw InputError("the largest ray set (" + std::to_string(rays) + " rays) needs about " +
                         std::to_string(need / 1'000'000) + " MB with " + std::to_string(variants) +
                         " tracers, more than the " + std::to_string(limit.bytes / 1'000'000) +
                         " MB of " + limit.source + "; choose a smaller --width/--height or --spp");
}

/// The variant the others are compared with: naive when measured, else the first of our
/// kernel, else the first.
std::size_t reference_index(const std::vector<Variant>& variants) {
    const auto first = [&](auto pred) {
        return std::size_t(std::find_if(variants.begin(), variants.end(), pred) - variants.begin());
    };
    const std::size_t naive = first([](const Variant& v) { return v.method == Method::naive; });
    if (naive < variants.size()) return naive;
    const std::size_t ours = first([](const Variant& v) { return v.method != Method::embree; });
    return ours < variants.size() ? ours : 0;
}

/// Times every variant on `rays`, repetitions interleaved, each in its own order (a shuffle
/// seeded by the repetition's number: the same for every run, and no variant always inherits
/// the memory state that one same predecessor left, pages handed back to the system or kept by
/// the allocator), calling
/// `frame_done` after each frame, then compares the hits of the last repetition with the
/// reference variant's.
SetRun run_set(const Scene& scene, std::span<const Triangle> triangles,
               const std::vector<Variant>& variants, const std::string& scene_name,
               const std::string& set_name, Query query, const std::vector<Ray>& rays, int threads,
               int repeat, const std::function<void()>& frame_done) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    std::size_t(threads));
    SetRun run{scene_name, set_name, query, rays.size(), threads, {}};
    std::vector<std::vector<Hit>> hits(variants.size(), std::vector<Hit>(rays.size()));
    for (const Variant& v : variants) {
        run.methods.emplace_back();
        run.methods.back().label = v.label;
        run.methods.back().method = v.method;
    }
    std::vector<std::size_t> order(variants.size());
    for (int r = 0; r < repeat; ++r) {
        std::iota(order.begin(), order.end(), std::size_t(0));
        std::shuffle(order.begin(), order.end(), std::mt19937(std::uint32_t(r)));
        for (const std::size_t i : order) {
            MethodRun& m = run.methods[i];
            const auto tracer = make_tracer(variants[i].method, EdacrtParams{}, variants[i].mode);
            auto start = std::chrono::steady_clock::now();
            tracer->set_scene(scene);
            m.prepare_seconds.push_back(seconds_since(start));
            start = std::chrono::steady_clock::now();
            m.stats = tracer->trace(rays, hits[i], query);
            m.trace_seconds.push_back(seconds_since(start));
            m.working_bytes = std::max(m.working_bytes, tracer->working_bytes());
            frame_done();
        }
    }
    const std::size_t ref = reference_index(variants);
    run.methods[ref].reference = true;
    for (std::size_t i = 0; i < variants.size(); ++i)
        if (i != ref)
            run.methods[i].agreement = compare_hits(
                triangles, rays, hits[ref], hits[i], query,
                variants[i].method != Method::embree && variants[ref].method != Method::embree);
    return run;
}

/// The --json and --markdown files, when asked for.
void write_outputs(const BenchOptions& o, const std::vector<int>& thread_counts,
                   const nlohmann::json& scenes_json, const nlohmann::json& rows_json,
                   const std::vector<Row>& rows, bool agreement_ok) {
    const nlohmann::json machine = machine_json();
    if (!o.json_path.empty()) {
        nlohmann::json settings = {{"width", o.width},
                                   {"height", o.height},
                                   {"spp", o.spp},
                                   {"sets", o.sets},
                                   {"methods", o.methods},
                                   {"repeat", o.repeat},
                                   {"threads", thread_counts},
                                   {"seed", o.seed},
                                   {"edacrt_params", "default preset"},
                                   {"ao_distance_fraction_of_diagonal", kAoDistanceFraction}};
        write_file(o.json_path,
                   nlohmann::json{{"command", "bench"},
                                  {"machine", machine},
                                  {"settings", settings},
                                  {"scenes", scenes_json},
                                  {"results", rows_json},
                                  {"agreement_ok", agreement_ok}}
                           .dump(2) +
                       "\n",
                   "benchmark JSON");
    }
    if (!o.markdown_path.empty())
        write_file(o.markdown_path,
                   "`edacrt bench`, " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                       " pixels, median of " + std::to_string(o.repeat) + " frames (set_scene + " +
                       "trace); " + machine["cpu"].get<std::string>() + ", " +
                       machine["date"].get<std::string>() + ", revision " +
                       machine["git_revision"].get<std::string>() + ".\n\n" +
                       markdown_table(rows, thread_counts.size() > 1),
                   "benchmark markdown");
}

void run(const BenchOptions& o) {
    check_distinct_files({{"--json", o.json_path}, {"--markdown", o.markdown_path}});
    if (o.dynamic) {
        DynamicBenchOptions d = o.animation;
        d.scenes = o.scenes;
        d.scenes_dir = o.scenes_dir;
        d.scenes_dir_required = !o.scenes.empty() || !o.scenes_dir.empty();
        d.methods = o.methods;
        d.spp = o.spp;
        d.width = o.width;
        d.height = o.height;
        d.threads = o.threads;
        d.seed = o.seed;
        d.json_path = o.json_path;
        d.markdown_path = o.markdown_path;
        run_dynamic_bench(d);
        return;
    }
    const std::vector<Variant> variants = make_variants(o.methods);
    const std::vector<SetChoice> sets = make_set_choices(o);
    check_memory(o, variants.size());
    check_writable(o.json_path, "--json");
    check_writable(o.markdown_path, "--markdown");
    if (!o.rays_dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(o.rays_dir, ec);
        if (ec || !std::filesystem::is_directory(o.rays_dir))
            throw InputError("--write-rays " + o.rays_dir + ": cannot create this directory" +
                             (ec ? " (" + ec.message() + ")" : std::string()));
    }
    const bool named = !o.scenes.empty();
    const std::vector<BenchScene> scenes =
        resolve_bench_scenes(named ? o.scenes : default_bench_scene_names(),
                             o.scenes_dir.empty() ? default_scenes_dir(EDACRT_SOURCE_DIR)
                                                  : std::filesystem::path(o.scenes_dir),
                             named || !o.scenes_dir.empty());
    if (scenes.empty()) throw InputError("no scene to measure (all were skipped)");

    const int all_threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
    std::vector<int> thread_counts = {all_threads};
    if (o.thread_sweep && all_threads > 1) thread_counts.insert(thread_counts.begin(), 1);
    const bool sweep = thread_counts.size() > 1;

    nlohmann::json scenes_json = nlohmann::json::array(), rows_json = nlohmann::json::array();
    std::vector<SetRun> runs;
    runs.reserve(scenes.size() * sets.size() * thread_counts.size());  // rows point into it
    std::vector<Row> rows;
    std::uint64_t disagreements = 0;
    std::cout << table_header(sweep) << std::flush;
    // Frames (set_scene + trace of one variant) are the unit of progress; a line per set.
    Progress progress(progress_style(o.quiet), "bench", Progress::Unit::rays);
    const double frames = double(scenes.size() * sets.size() * thread_counts.size() *
                                 std::size_t(o.repeat) * variants.size());
    double frames_done = 0.0, rays_done = 0.0;
    for (const BenchScene& bench_scene : scenes) {
        progress.begin("loading " + bench_scene.name);
        progress.clear();
        const Scene scene = load_scene_verbose(bench_scene.spec);
        if (scene.triangle_count() == 0) throw InputError(scene.source + ": no triangles");
        const BenchView view = bench_view(scene, bench_scene.name);
        progress.print(std::cerr, "bench: " + bench_scene.name + ": " +
                                      (view.inside ? "inside" : "outside") + " view, " +
                                      view.reason);
        const BenchRays bench_rays(scene, view.camera, o.width, o.height, o.seed);
        const auto vec = [](glm::vec3 v) { return nlohmann::json{v.x, v.y, v.z}; };
        scenes_json.push_back({{"name", bench_scene.name},
                               {"source", scene.source},
                               {"triangles", scene.triangle_count()},
                               {"view",
                                {{"inside", view.inside},
                                 {"reason", view.reason},
                                 {"eye", vec(view.camera.eye)},
                                 {"look_at", vec(view.camera.look_at)},
                                 {"up", vec(view.camera.up)},
                                 {"vfov_degrees", view.camera.vfov_degrees}}},
                               {"shadow_light", bench_rays.light()}});
        const FrameVector<Triangle> triangles = gather_triangles(scene);
        for (const SetChoice& set : sets) {
            const std::vector<Ray> rays = make_rays(bench_rays, set);
            if (!o.rays_dir.empty())  // for `edacrt trace` of one set alone
                write_rays(std::filesystem::path(o.rays_dir) /
                               (bench_scene.name + "_" + set.name + ".rays"),
                           rays);
            const Query query = set.kind == RaySetKind::ao || set.kind == RaySetKind::shadow
                                    ? Query::any
                                    : Query::closest;
            for (int threads : thread_counts) {
                const std::string what = bench_scene.name + " " + set.name + ", " +
                                         std::to_string(rays.size()) + " rays, " +
                                         std::to_string(threads) + " thread(s)";
                progress.begin(what);
                runs.push_back(run_set(scene, triangles, variants, bench_scene.name, set.name,
                                       query, rays, threads, o.repeat, [&] {
                                           ++frames_done;
                                           rays_done += double(rays.size());
                                           progress.update(frames_done / frames, rays_done, what);
                                       }));
                progress.step(frames_done / frames, rays_done, what);
            }
            // Print once every thread count of the set is in (the scaling needs both).
            const SetRun* single = sweep ? &runs[runs.size() - thread_counts.size()] : nullptr;
            for (std::size_t k = runs.size() - thread_counts.size(); k < runs.size(); ++k)
                for (const Row& row : make_rows(runs[k], &runs[k] == single ? nullptr : single)) {
                    rows.push_back(row);
                    rows_json.push_back(row_json(row));
                    if (row.shown) {
                        std::string text = table_row(row, sweep);
                        if (text.ends_with('\n')) text.pop_back();
                        progress.print(std::cout, text);
                    }
                    if (row.method->agreement.disagreements) {
                        disagreements += row.method->agreement.disagreements;
                        progress.print(
                            std::cerr,
                            "bench: DISAGREEMENT: " + row.method->label +
                                " differs from the "
                                "reference on " +
                                std::to_string(row.method->agreement.disagreements) + " rays of " +
                                row.run->scene + " " + row.run->set + " (first: ray " +
                                std::to_string(row.method->agreement.first_disagreement) + ")");
                    }
                }
        }
    }

    progress.finish();
    write_outputs(o, thread_counts, scenes_json, rows_json, rows, disagreements == 0);
    if (disagreements)
        throw std::runtime_error("the methods disagree on " + std::to_string(disagreements) +
                                 " rays (see DISAGREEMENT above)");
}

}  // namespace

std::function<void()> add_bench_command(CLI::App& app) {
    auto options = std::make_shared<BenchOptions>();
    BenchOptions& o = *options;
    CLI::App* command = app.add_subcommand(
        "bench",
        "Time every method on the same rays, frame by frame: set_scene() (per-frame "
        "structures) plus trace(), nothing kept between frames, repetitions interleaved across "
        "methods; then check that all methods found the same hits (exit 2 if not).\n"
        "Example: edacrt bench --scene bunny --width 256 --height 256 --json out/bench.json");
    command->add_option("--scenes", o.scenes_dir,
                        "directory of the large scenes (default: $EDACRT_SCENES, else "
                        "../shared/scenes beside the repository)");
    command->add_option("--scene", o.scenes,
                        "a scene to measure (repeatable): bunny, dragon, buddha, suzanne, sponza, "
                        "sibenik, conference, cornell, spot, teapot, an OBJ path or builtin:... "
                        "(default: bunny, sponza, sibenik, conference, cornell, spot, teapot; "
                        "absent ones are skipped)");
    command->add_option("--sets", o.sets, flags::enum_option_help("ray sets", kRaySetKinds))
        ->delimiter(',')
        ->capture_default_str();
    command->add_option("--spp", o.spp, "samples per pixel of the camera sets, one set each")
        ->delimiter(',')
        ->check(CLI::Range(1, 1024))
        ->capture_default_str();
    command
        ->add_option("--methods", o.methods,
                     "methods: " + enum_names(kMethods) +
                         " (embree: all three modes, the fastest is the ratio base; naive is "
                         "slow)")
        ->delimiter(',')
        ->capture_default_str();
    command->add_option("--width", o.width, "pixels per row")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    command->add_option("--height", o.height, "rows")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    command->add_option("--repeat", o.repeat, "frames per method and set (median and min)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    command->add_option("--threads", o.threads, "worker threads (0: all cores)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    add_quiet_option(*command, o.quiet);
    command->add_flag("--thread-sweep", o.thread_sweep,
                      "also run on 1 thread and report time(1 thread) / time(--threads)");
    command->add_option("--seed", o.seed, "seed of the jitter, bounces and light samples")
        ->capture_default_str();
    command->add_option("--json", o.json_path, "write every measurement and the machine here");
    command->add_option("--markdown", o.markdown_path, "write the table as markdown here");
    CLI::Option* write_rays =
        command->add_option("--write-rays", o.rays_dir,
                            "also write each set's rays to DIR/SCENE_SET.rays (for edacrt trace; "
                            "any-hit sets are ao and shadow)");
    const std::string dynamic = "Dynamic scenes (--dynamic)";
    command
        ->add_flag("--dynamic", o.dynamic,
                   "animate the scenes (default: bunny, sponza) and time every method frame by "
                   "frame on camera rays: update (bvh and embree: rebuild, refit; embree: "
                   "dynamic; edacrt, dacrt: none) + trace, and a sweep of rays per triangle")
        ->excludes(write_rays)  // its frames are camera rays made per frame
        ->group(dynamic);
    command->add_option("--animate", o.animation.animation, "the animation (see render --help)")
        ->capture_default_str()
        ->group(dynamic);
    command->add_option("--frames", o.animation.frames, "timed frames per set (medians)")
        ->capture_default_str()
        ->group(dynamic);
    command
        ->add_option("--rays-per-triangle", o.animation.rays_per_triangle,
                     "the sweep: 1-spp camera sets of these many rays per triangle")
        ->capture_default_str()
        ->delimiter(',')
        ->group(dynamic);
    return [options] { run(*options); };
}

}  // namespace edacrt::cli
