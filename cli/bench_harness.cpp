// edacrt bench, still and animated. Divide-and-conquer ray tracing keeps no structure, so still
// frames are timed as a structure-keeping method must pay for them when nothing is kept, and
// animated ones show what geometry that changes every frame costs each method (Mora 2011, Afra
// 2012): a BVH is rebuilt or refitted, EDACRT pays nothing extra.
#include "bench_harness.h"

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

#include "bench_report.h"
#include "bench_scenes.h"
#include "bench_variant.h"
#include "common_options.h"
#include "progress.h"
#include "render/render_memory.h"
#include "scene/animation.h"
#include "scene/scene_paths.h"
#include "trace/ray_file.h"
#include "util/error.h"
#include "util/output_file.h"

namespace edacrt::cli {
namespace {

/// The variants of `names`, each once: a method, or a spec METHOD:KEY=VALUE... with settings
/// of its own (bench_variant.h). Still, Embree in each of its modes (the fastest
/// stands for it in the reports). Animated, the BVH and Embree in each of their ways to take a
/// frame, and EDACRT also without pre-split pieces, whose clipping is most of its per-frame
/// work on large triangles.
std::vector<Variant> make_variants(const std::vector<std::string>& names, bool animated) {
    std::vector<Variant> variants;
    const auto add = [&](std::string label, Method method) -> Variant& {
        variants.push_back({std::move(label), method});
        return variants.back();
    };
    for (const std::string& name : names) {
        if (name.find(':') != std::string::npos) {  // a variant with its own settings
            if (animated) throw InputError("--methods " + name + ": --dynamic takes methods only");
            Variant v = parse_variant(name);
            if (std::none_of(variants.begin(), variants.end(),
                             [&](const Variant& o) { return o.label == v.label; }))
                variants.push_back(std::move(v));
            continue;
        }
        const Method method = parse_enum_or_throw(kMethods, name);
        if (std::any_of(variants.begin(), variants.end(), [&](const Variant& v) {
                return v.label == name || v.label.starts_with(name + "/");
            }))
            continue;
        if (method == Method::naive)
            std::cerr << "bench: warning: naive tests every ray against every triangle; expect "
                         "hours on large scenes\n";
        if (method == Method::embree) make_tracer(Method::embree);  // throws without Embree
        const std::string prefix = std::string(enum_name(kMethods, method)) + "/";
        if (method == Method::embree && !animated) {
            for (EmbreeMode mode : {EmbreeMode::packet8, EmbreeMode::single, EmbreeMode::stream})
                add(prefix + std::string(enum_name(kEmbreeModes, mode)), method).mode = mode;
        } else if ((method == Method::embree || method == Method::bvh) && animated) {
            for (SceneUpdate how : {SceneUpdate::rebuild, SceneUpdate::dynamic, SceneUpdate::refit})
                if (method == Method::embree || how != SceneUpdate::dynamic)
                    add(prefix + std::string(enum_name(kSceneUpdates, how)), method).how = how;
        } else {
            add(name, method);
            if (method == Method::edacrt && animated)
                add("edacrt/presplit-0", method).params.presplit = 0.0f;
        }
    }
    if (variants.empty()) throw InputError("--methods: no method to measure");
    return variants;
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

void add(Agreement& total, const Agreement& frame) {
    if (total.first_disagreement < 0) total.first_disagreement = frame.first_disagreement;
    total.rays += frame.rays;
    total.ties += frame.ties;
    total.tolerated += frame.tolerated;
    total.disagreements += frame.disagreements;
}

/// What a set's frames trace. Still (`animation` null): `scene` as it is, every frame a new
/// tracer, set_scene() and trace(), nothing kept. Animated: the tracers kept from frame to
/// frame; they first take the scene at t = 0, untimed (the structure a previous frame left),
/// then frame f of `count` at t = duration * (f + 1) / (count + 1) with update_scene().
struct Frames {
    Scene& scene;
    Animation* animation;
    int count;
};

/// The order in which the variants take frame `f`. Still: a shuffle seeded by `f` (the same
/// for every run, and no variant always inherits the memory state that one same predecessor
/// left, pages handed back to the system or kept by the allocator). Animated: rotated, the
/// first to go moving on by one every frame.
std::vector<std::size_t> frame_order(std::size_t variants, int f, bool animated) {
    std::vector<std::size_t> order(variants);
    std::iota(order.begin(), order.end(), std::size_t(0));
    if (animated)
        std::rotate(order.begin(), order.begin() + std::ptrdiff_t((f + 1) % variants), order.end());
    else
        std::shuffle(order.begin(), order.end(), std::mt19937(std::uint32_t(f)));
    return order;
}

/// The parameters of still frame `f`: a new sampling seed each frame. Sampled hit ratios make
/// the recursion's tree depend on the draw, and one draw's tree can take 0.8-1.3x the time of
/// another's on the same rays (Conference diffuse bounces), so a median over frames is one over
/// draws, as a render's passes see them, not the luck of one seed.
EdacrtParams frame_params(EdacrtParams params, int f) {
    params.seed += std::uint32_t(f);
    return params;
}

/// Times every variant over the frames on `rays` at `run.threads` threads, calling
/// `frame_done` after each variant's frame, and compares the hits with the reference variant's:
/// on every animated frame, on the last still one (the others are the same).
SetRun run_set(const Frames& frames, const std::vector<Variant>& variants, SetRun run,
               const std::vector<Ray>& rays, const std::function<void()>& frame_done) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    std::size_t(run.threads));
    const bool animated = frames.animation != nullptr;
    run.animated = animated;
    run.rays = rays.size();
    run.triangles = frames.scene.triangle_count();
    run.methods.resize(variants.size());
    for (std::size_t i = 0; i < variants.size(); ++i) run.methods[i].variant = variants[i];
    const std::size_t ref = reference_index(variants);
    run.methods[ref].reference = true;

    std::vector<std::unique_ptr<Tracer>> tracers(variants.size());
    if (animated) {
        frames.animation->frame(0.0, frames.scene);
        for (std::size_t i = 0; i < variants.size(); ++i) {
            tracers[i] = make_tracer(variants[i].method, variants[i].params, variants[i].mode,
                                     variants[i].bvh);
            tracers[i]->update_scene(frames.scene, variants[i].how);
        }
    }
    std::vector<std::vector<Hit>> hits(variants.size(), std::vector<Hit>(rays.size()));
    FrameVector<Triangle> triangles;
    for (int f = 0; f < frames.count; ++f) {
        if (animated) {
            const auto start = std::chrono::steady_clock::now();
            frames.animation->frame(frames.animation->duration() * (f + 1) / (frames.count + 1),
                                    frames.scene);
            run.animate_seconds.push_back(seconds_since(start));
        }
        for (const std::size_t i : frame_order(variants.size(), f, animated)) {
            const Variant& v = variants[i];
            MethodRun& m = run.methods[i];
            if (!animated)
                tracers[i] = make_tracer(v.method, frame_params(v.params, f), v.mode, v.bvh);
            const UpdateStats update = tracers[i]->update_scene(frames.scene, v.how);
            m.work = update.work;
            m.prepare_seconds.push_back(update.seconds);
            const auto start = std::chrono::steady_clock::now();
            m.stats += tracers[i]->trace(rays, hits[i], run.query);
            m.trace_seconds.push_back(seconds_since(start));
            m.working_bytes = std::max(m.working_bytes, tracers[i]->working_bytes());
            if (!animated) tracers[i].reset();
            frame_done();
        }
        if (!animated && f + 1 < frames.count) continue;
        gather_triangles(frames.scene, triangles);
        for (std::size_t i = 0; i < variants.size(); ++i)
            if (i != ref)
                add(run.methods[i].agreement,
                    compare_hits(triangles, rays, hits[ref], hits[i], run.query,
                                 variants[i].method != Method::embree &&
                                     variants[ref].method != Method::embree));
    }
    return run;
}

/// The sets every scene is measured on. Still: --sets, a camera set per --spp. Animated: the
/// camera sets, then the sweep.
std::vector<RaySet> make_sets(const BenchOptions& o) {
    std::vector<RaySet> sets;
    const auto add_camera_sets = [&] {
        for (const RaySet& set : camera_sets(o.spp)) sets.push_back(set);
    };
    if (o.dynamic) {
        add_camera_sets();
        for (const double r : o.rays_per_triangle)
            sets.push_back({"sweep", RaySetKind::sweep, 1, r});
        return sets;
    }
    for (const std::string& name : o.sets) {
        const RaySetKind kind = parse_enum_or_throw(kRaySetKinds, name);
        if (kind == RaySetKind::camera)
            add_camera_sets();
        else
            sets.push_back({name, kind});
    }
    return sets;
}

void validate_animation(const BenchOptions& o) {
    if (o.frames < 1 || o.frames > 1000) throw InputError("--frames must be from 1 to 1000");
    for (const double r : o.rays_per_triangle)
        if (!(r > 0.0 && r <= 1e4))
            throw InputError("--rays-per-triangle values must be in (0, 10000]");
    if (o.spp.empty() && o.rays_per_triangle.empty())
        throw InputError("nothing to measure: give --spp or --rays-per-triangle");
}

/// Refuses a set of `rays` rays that cannot fit (render_memory.h): the rays, a hit buffer per
/// variant, the tracers' own per-ray state (one tracer at a time when still, all of them kept
/// when animated) and `kept` bytes beside. Scenes come on top.
void check_memory(std::uint64_t rays, std::size_t variants, bool animated, std::uint64_t kept,
                  const std::string& advice) {
    if (rays > std::uint64_t(1) << 31)
        throw InputError("a set of " + std::to_string(rays) +
                         " rays is more than the 2^31 supported; choose " + advice);
    const std::uint64_t state = trace_bytes_per_ray() - sizeof(Ray) - sizeof(Hit);
    const std::uint64_t need =
        rays * (sizeof(Ray) + variants * sizeof(Hit) + (animated ? variants : 1) * state) + kept;
    const MemoryLimit limit = memory_limit();
    if (need > limit.bytes)
        throw InputError("a set of " + std::to_string(rays) + " rays needs about " +
                         std::to_string(need / 1'000'000) + " MB with " + std::to_string(variants) +
                         " tracers, more than the " + std::to_string(limit.bytes / 1'000'000) +
                         " MB of " + limit.source + "; choose " + advice);
}

/// The largest camera set, before any scene is loaded; still secondary sets keep the 1-spp
/// camera rays and hits they start from.
void check_camera_memory(const BenchOptions& o, const std::vector<RaySet>& sets,
                         std::size_t variants) {
    if (o.spp.empty()) return;
    const std::uint64_t pixels = std::uint64_t(o.width) * std::uint64_t(o.height);
    const bool secondary = std::any_of(sets.begin(), sets.end(), [](const RaySet& s) {
        return s.kind != RaySetKind::camera && s.kind != RaySetKind::sweep;
    });
    check_memory(pixels * std::uint64_t(*std::max_element(o.spp.begin(), o.spp.end())), variants,
                 o.dynamic, secondary ? pixels * (sizeof(Ray) + sizeof(Hit)) : 0,
                 "a smaller --width/--height or --spp");
}

/// The --scene ones, else the manifest's default list; an animation that brings its own
/// geometry is the one scene, named after its file.
std::vector<BenchScene> bench_scenes(const BenchOptions& o) {
    if (o.dynamic && animation_has_geometry(o.animation)) {
        if (!o.scenes.empty())
            throw InputError("the animation " + o.animation +
                             " names its own geometry: give no --scene with it");
        return {{std::filesystem::path(o.animation).stem().string(), ""}};
    }
    const bool named = !o.scenes.empty();
    return resolve_bench_scenes(
        named ? o.scenes : bench_scene_list(o.dynamic ? "bench_dynamic" : "bench"),
        o.scenes_dir.empty() ? default_scenes_dir(EDACRT_SOURCE_DIR)
                             : std::filesystem::path(o.scenes_dir),
        named || !o.scenes_dir.empty());
}

nlohmann::json scene_json(const BenchScene& bench_scene, const AnimatedScene& animated,
                          const BenchView& view, const BenchRays& rays) {
    const Scene& scene = animated.scene;
    nlohmann::json json = {{"name", bench_scene.name},
                           {"source", scene.source},
                           {"triangles", scene.triangle_count()}};
    if (animated.animation) {
        json.update({{"animation", animated.animation->spec()},
                     {"duration_seconds", animated.animation->duration()},
                     {"view_inside", view.inside}});
        return json;
    }
    const auto vec = [](glm::vec3 v) { return nlohmann::json{v.x, v.y, v.z}; };
    json.update({{"view",
                  {{"inside", view.inside},
                   {"reason", view.reason},
                   {"eye", vec(view.camera.eye)},
                   {"look_at", vec(view.camera.look_at)},
                   {"up", vec(view.camera.up)},
                   {"vfov_degrees", view.camera.vfov_degrees}}},
                 {"shadow_light", rays.light()}});
    return json;
}

nlohmann::json settings_json(const BenchOptions& o, const std::vector<int>& thread_counts) {
    nlohmann::json json = {
        {"width", o.width}, {"height", o.height},
        {"spp", o.spp},     {"methods", o.methods},
        {"seed", o.seed},   {"edacrt_params", "defaults, or as a method spec sets them"}};
    if (o.dynamic)
        json.update({{"animation", o.animation},
                     {"frames", o.frames},
                     {"rays_per_triangle", o.rays_per_triangle},
                     {"threads", thread_counts.front()},
                     {"embree_mode", enum_name(kEmbreeModes, kDefaultEmbreeMode)}});
    else
        json.update({{"sets", o.sets},
                     {"repeat", o.repeat},
                     {"threads", thread_counts},
                     {"ao_distance_fraction_of_diagonal", kAoDistanceFraction}});
    return json;
}

/// The --json and --markdown files, when asked for.
void write_outputs(const BenchOptions& o, const std::vector<int>& thread_counts,
                   const nlohmann::json& scenes, const std::vector<Row>& rows,
                   const std::vector<Crossover>& found, bool agreement_ok) {
    const nlohmann::json machine = machine_json();
    if (!o.json_path.empty()) {
        nlohmann::json results = nlohmann::json::array(), crossovers = nlohmann::json::array();
        for (const Row& row : rows) results.push_back(row_json(row));
        for (const Crossover& c : found) crossovers.push_back(crossover_json(c));
        nlohmann::json json = {{"command", o.dynamic ? "bench --dynamic" : "bench"},
                               {"machine", machine},
                               {"settings", settings_json(o, thread_counts)},
                               {"scenes", scenes},
                               {"results", results},
                               {"agreement_ok", agreement_ok}};
        if (o.dynamic) json["crossovers"] = crossovers;
        write_file(o.json_path, json.dump(2) + "\n", "benchmark JSON");
    }
    if (o.markdown_path.empty()) return;
    const std::string what = o.dynamic
                                 ? "`edacrt bench --dynamic`, " + o.animation + ", " +
                                       std::to_string(o.frames) + " frames per set (medians), " +
                                       std::to_string(thread_counts.front()) + " thread(s); "
                                 : "`edacrt bench`, " + std::to_string(o.width) + "x" +
                                       std::to_string(o.height) + " pixels, median of " +
                                       std::to_string(o.repeat) + " frames (set_scene + trace); ";
    std::string text = what + machine["cpu"].get<std::string>() + ", " +
                       machine["date"].get<std::string>() + ", revision " +
                       machine["git_revision"].get<std::string>() + ".\n\n" +
                       markdown_table(rows, {o.dynamic, thread_counts.size() > 1});
    if (o.dynamic) text += "\n" + crossover_markdown_table(found);
    write_file(o.markdown_path, text, "benchmark markdown");
}

/// The ray file --write-rays writes for one scene and set.
std::string rays_file(const BenchOptions& o, const BenchScene& scene, const RaySet& set) {
    return (std::filesystem::path(o.rays_dir) / (scene.name + "_" + set.name + ".rays")).string();
}

}  // namespace

void run_bench(const BenchOptions& o) {
    std::vector<Variant> variants;
    std::vector<RaySet> sets;
    check_flags([&] {
        if (o.dynamic) validate_animation(o);
        variants = make_variants(o.methods, o.dynamic);
        sets = make_sets(o);
    });
    const std::vector<BenchScene> scenes = bench_scenes(o);
    if (scenes.empty()) throw InputError("no scene to measure (all were skipped)");
    // The ray files' names are known up front: no report may share one, nor any a scene file.
    std::vector<NamedPath> outputs = {{"--json", o.json_path}, {"--markdown", o.markdown_path}};
    std::vector<NamedPath> inputs;
    for (const BenchScene& scene : scenes) {
        inputs.push_back({"--scene", scene.spec});
        if (!o.rays_dir.empty())
            for (const RaySet& set : sets)
                outputs.push_back({"--write-rays", rays_file(o, scene, set)});
    }
    check_distinct_files(outputs, inputs);
    check_camera_memory(o, sets, variants.size());
    check_writable(o.json_path, "--json");
    check_writable(o.markdown_path, "--markdown");
    if (!o.rays_dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(o.rays_dir, ec);
        if (ec || !std::filesystem::is_directory(o.rays_dir))
            throw InputError("--write-rays " + o.rays_dir + ": cannot create this directory" +
                             (ec ? " (" + ec.message() + ")" : std::string()));
    }

    const int all_threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
    std::vector<int> thread_counts = {all_threads};
    if (o.thread_sweep && !o.dynamic && all_threads > 1)
        thread_counts.insert(thread_counts.begin(), 1);
    const TableLayout layout{o.dynamic, thread_counts.size() > 1};
    const int frame_count = o.dynamic ? o.frames : o.repeat;

    nlohmann::json scenes_json = nlohmann::json::array();
    std::vector<SetRun> runs;
    runs.reserve(scenes.size() * sets.size() * thread_counts.size());  // rows point into it
    std::vector<Row> rows;
    std::uint64_t disagreements = 0;
    std::cout << table_header(layout) << std::flush;
    // Frames (the update and trace of one variant) are the unit of progress; a line per set.
    Progress progress(progress_style(o.quiet), "bench", Progress::Unit::rays);
    const double frames = double(scenes.size() * sets.size() * thread_counts.size() *
                                 std::size_t(frame_count) * variants.size());
    double frames_done = 0.0, rays_done = 0.0;
    for (const BenchScene& bench_scene : scenes) {
        progress.begin("loading " + bench_scene.name);
        progress.clear();
        AnimatedScene animated = o.dynamic
                                     ? load_animated_scene(bench_scene.spec, o.animation)
                                     : AnimatedScene{load_scene_verbose(bench_scene.spec), nullptr};
        Scene& scene = animated.scene;
        check_outputs_spare_scene(outputs, scene);
        const std::size_t triangles = scene.triangle_count();
        if (triangles == 0) throw InputError(scene.source + ": no triangles");
        const BenchView view = bench_view(scene, bench_scene.name);
        progress.print(std::cerr,
                       "bench: " + bench_scene.name + ": " +
                           (o.dynamic ? std::to_string(triangles) + " triangles animated by " +
                                            animated.animation->spec() + ", "
                                      : std::string()) +
                           (view.inside ? "inside" : "outside") + " view, " + view.reason);
        BenchRays bench_rays(scene, view.camera, o.width, o.height, o.seed);
        scenes_json.push_back(scene_json(bench_scene, animated, view, bench_rays));
        const Frames scene_frames{scene, animated.animation.get(), frame_count};
        for (const RaySet& set : sets) {
            if (set.kind == RaySetKind::sweep)
                check_memory(std::uint64_t(set.rays_per_triangle * double(triangles)) + 1,
                             variants.size(), true, 0, "smaller --rays-per-triangle values");
            const std::vector<Ray> rays = bench_rays.make(set);
            if (!o.rays_dir.empty())  // for `edacrt trace` of one set alone
                write_rays(rays_file(o, bench_scene, set), rays);
            for (int threads : thread_counts) {
                const std::string what = bench_scene.name + " " + set.name + ", " +
                                         std::to_string(rays.size()) + " rays, " +
                                         (o.dynamic ? std::to_string(o.frames) + " frames, " : "") +
                                         std::to_string(threads) + " thread(s)";
                progress.begin(what);
                SetRun run;
                run.scene = bench_scene.name;
                run.set = set.name;
                run.query = set.query();
                run.threads = threads;
                run.spp = set.spp;
                runs.push_back(run_set(scene_frames, variants, std::move(run), rays, [&] {
                    ++frames_done;
                    rays_done += double(rays.size());
                    progress.update(frames_done / frames, rays_done, what);
                }));
                progress.step(frames_done / frames, rays_done, what);
            }
            // Print once every thread count of the set is in (the scaling needs both).
            const std::size_t first = runs.size() - thread_counts.size();
            const SetRun* single = layout.thread_sweep ? &runs[first] : nullptr;
            for (std::size_t k = first; k < runs.size(); ++k)
                for (const Row& row : make_rows(runs[k], &runs[k] == single ? nullptr : single)) {
                    rows.push_back(row);
                    if (row.shown) {
                        std::string text = table_row(row, layout);
                        if (text.ends_with('\n')) text.pop_back();
                        progress.print(std::cout, text);
                    }
                    const Agreement& a = row.method->agreement;
                    if (!a.disagreements) continue;
                    disagreements += a.disagreements;
                    progress.print(std::cerr, "bench: DISAGREEMENT: " + row.method->variant.label +
                                                  " differs from the reference on " +
                                                  std::to_string(a.disagreements) + " rays of " +
                                                  row.run->scene + " " + row.run->set +
                                                  " (first: ray " +
                                                  std::to_string(a.first_disagreement) + ")");
                }
        }
    }
    progress.finish();

    const std::vector<Crossover> found = o.dynamic ? crossovers(runs) : std::vector<Crossover>{};
    if (!found.empty()) std::cout << "\n" << crossover_markdown_table(found);
    write_outputs(o, thread_counts, scenes_json, rows, found, disagreements == 0);
    if (disagreements)
        throw std::runtime_error("the methods disagree on " + std::to_string(disagreements) +
                                 " rays (see DISAGREEMENT above)");
}

}  // namespace edacrt::cli
