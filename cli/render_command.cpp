// edacrt render: primary rays with eye-light shading, to PNG.
#include <chrono>
#include <iostream>
#include <vector>

#include "camera_options.h"
#include "commands.h"
#include "common_options.h"
#include "render/eye_light.h"
#include "stats_json.h"
#include "util/error.h"

namespace edacrt::cli {
namespace {

struct RenderOptions {
    CommonOptions common;
    EyeLightSettings settings;
    std::string out = "out/render.png";
    CameraOptions camera;
};

void run(const RenderOptions& o) {
    const auto threads = apply_thread_limit(o.common);
    const Method method = parse_method(o.common.method);
    const auto tracer = make_tracer(o.common);  // rejects bad parameters early
    const Scene scene = load_scene_verbose(o.common.scene);
    const Camera camera = choose_camera(scene, o.camera);

    auto start = std::chrono::steady_clock::now();
    tracer->set_scene(scene);
    const double prepare_seconds = seconds_since(start);

    EyeLightSettings settings = o.settings;
    TraceDetail detail;
    if (!o.common.stats_path.empty()) settings.detail = &detail;
    start = std::chrono::steady_clock::now();
    const EyeLightResult result = render_eye_light(scene, camera, *tracer, settings);
    const double render_seconds = seconds_since(start);

    const std::filesystem::path out(o.out);
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    write_png(out, result.image);

    const double mrays = double(result.stats.rays) / result.trace_seconds * 1e-6;
    std::cout << "rendered " << o.settings.width << "x" << o.settings.height << " at "
              << o.settings.spp << " spp with " << method_name(method) << ": " << result.stats.rays
              << " rays traced in " << result.trace_seconds << " s (" << mrays
              << " Mrays/s), written to " << o.out << "\n";

    nlohmann::json stats = {{"command", "render"},
                            {"scene", scene.source},
                            {"triangles", scene.triangle_count()},
                            {"method", method_name(method)},
                            {"embree_mode", o.common.embree_mode},
                            {"width", o.settings.width},
                            {"height", o.settings.height},
                            {"spp", o.settings.spp},
                            {"seed", o.settings.seed},
                            {"rays", result.stats.rays},
                            {"ray_box_tests", result.stats.ray_box_tests},
                            {"ray_triangle_tests", result.stats.ray_triangle_tests},
                            {"prepare_seconds", prepare_seconds},
                            {"trace_seconds", result.trace_seconds},
                            {"render_seconds", render_seconds},
                            {"mrays_per_second", mrays}};
    stats["detail"] = to_json(detail);
    stats["detail"]["from"] = "an extra, untimed pass of the first sample's camera rays";
    write_stats(o.common, stats);
}

}  // namespace

std::function<void()> add_render_command(CLI::App& app) {
    auto options = std::make_shared<RenderOptions>();
    RenderOptions& o = *options;
    CLI::App* command = app.add_subcommand(
        "render",
        "Render camera rays with eye-light shading to a PNG.\n"
        "Example: edacrt render --scene assets/cornell-box/CornellBox-Original.obj "
        "--out out/cornell.png");
    add_common_options(*command, o.common);
    command->add_option("--width", o.settings.width, "image width in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    command->add_option("--height", o.settings.height, "image height in pixels")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    command->add_option("--spp", o.settings.spp, "samples per pixel (jittered when > 1)")
        ->check(CLI::Range(1, 65536))
        ->capture_default_str();
    command->add_option("--seed", o.settings.seed, "seed of the pixel jitter")
        ->capture_default_str();
    command->add_option("--out", o.out, "output PNG")->capture_default_str();
    add_camera_options(*command, o.camera);
    return [options] { run(*options); };
}

}  // namespace edacrt::cli
