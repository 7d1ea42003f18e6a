// edacrt trace: a ray file in, a hit file out, with any method; the differential-testing tool.
#include <algorithm>
#include <chrono>
#include <iostream>

#include "commands.h"
#include "common_options.h"
#include "progress.h"
#include "trace/ray_file.h"
#include "trace/stats_json.h"

namespace edacrt::cli {
namespace {

struct TraceOptions {
    CommonOptions common;
    std::string rays_path;
    std::string out_path;
    bool any_hit = false;
};

void run(const TraceOptions& o) {
    const auto threads = apply_thread_limit(o.common);
    const std::vector<NamedPath> outputs = {{"--out", o.out_path},
                                            {"--stats", o.common.stats_path}};
    check_distinct_files(outputs, {{"--rays", o.rays_path}, {"--scene", o.common.scene}});
    const auto tracer = make_tracer(o.common);  // rejects bad parameters early
    const std::vector<Ray> rays = read_rays(o.rays_path);
    const Scene scene = load_scene_verbose(o.common.scene);
    check_outputs_spare_scene(outputs, scene);

    // One batch: its fraction is unknown until it ends, so a terminal shows time passing.
    Progress progress(progress_style(o.common.quiet), "trace", Progress::Unit::rays);
    const std::string method(enum_name(kMethods, o.common.method));
    progress.begin("set_scene (" + method + ")");
    auto start = std::chrono::steady_clock::now();
    tracer->set_scene(scene);
    const double prepare_seconds = seconds_since(start);
    progress.step(-1.0, 0.0, "prepared " + method);

    std::vector<Hit> hits(rays.size());
    progress.begin("tracing " + std::to_string(rays.size()) + " rays");
    start = std::chrono::steady_clock::now();
    const Query query = o.any_hit ? Query::any : Query::closest;
    const TraceStats stats = tracer->trace(rays, hits, query);
    const double trace_seconds = seconds_since(start);
    progress.step(1.0, double(rays.size()), "traced " + std::to_string(rays.size()) + " rays");
    progress.finish();
    write_hits(o.out_path, hits);

    const auto hit_count =
        std::count_if(hits.begin(), hits.end(), [](const Hit& h) { return h.hit(); });
    const double mrays = double(rays.size()) / trace_seconds * 1e-6;
    std::cout << "traced " << rays.size() << " rays (" << enum_name(kQueries, query) << " hit"
              << ") with " << method << " in " << trace_seconds << " s: " << mrays << " Mrays/s; "
              << hit_count << " hits; prepare " << prepare_seconds << " s; " << stats.ray_box_tests
              << " ray-box and " << stats.ray_triangle_tests << " ray-triangle tests\n";

    nlohmann::json report = {{"command", "trace"},
                             {"scene", scene.source},
                             {"triangles", scene.triangle_count()},
                             {"method", method},
                             {"embree_mode", enum_name(kEmbreeModes, o.common.embree_mode)},
                             {"query", enum_name(kQueries, query)},
                             {"rays", stats.rays},
                             {"hits", hit_count},
                             {"ray_box_tests", stats.ray_box_tests},
                             {"ray_triangle_tests", stats.ray_triangle_tests},
                             {"prepare_seconds", prepare_seconds},
                             {"trace_seconds", trace_seconds},
                             {"mrays_per_second", mrays}};
    if (!o.common.stats_path.empty()) {
        TraceDetail detail;
        std::vector<Hit> again(rays.size());
        tracer->trace(rays, again, query, &detail);
        report["detail"] = stats_json(detail);
        report["detail"]["from"] = "an extra, untimed pass of the same rays";
    }
    write_stats(o.common, report);
}

}  // namespace

std::function<void()> add_trace_command(CLI::App& app) {
    auto options = std::make_shared<TraceOptions>();
    TraceOptions& o = *options;
    CLI::App* command = app.add_subcommand(
        "trace",
        "Trace a binary ray file and write a binary hit file.\n"
        "Ray record: 8 float32 'ox oy oz dx dy dz tmin tmax' (32 bytes, little-endian).\n"
        "Hit record: float32 t (+inf on a miss), int32 prim (-1 on a miss), float32 u, v.");
    add_common_options(*command, o.common);
    command->add_option("--rays", o.rays_path, "input ray file")->required();
    command->add_option("--out", o.out_path, "output hit file")->required();
    command->add_flag(
        "--any-hit", o.any_hit,
        "occlusion query: prim >= 0 when anything blocks the ray (t, u, v of some hit)");
    return [options] { run(*options); };
}

}  // namespace edacrt::cli
