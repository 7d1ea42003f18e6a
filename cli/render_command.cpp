// edacrt render: the progressive wavefront renderer (primary, ao or path), to an image file
// whose extension chooses the format.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <vector>

#include "animation_options.h"
#include "camera_flags.h"
#include "commands.h"
#include "common_options.h"
#include "enum_flags.h"
#include "interrupt.h"
#include "parse_command_line.h"
#include "progress.h"
#include "render/image_format.h"
#include "render/render_memory.h"
#include "render/render_metadata.h"
#include "render/renderer.h"
#include "render/sampler.h"
#include "trace/stats_json.h"
#include "util/error.h"
#include "util/output_file.h"

namespace edacrt::cli {
namespace {

struct RenderOptions {
    CommonOptions common;
    AnimationOptions animation;
    RenderSettings settings;
    int spp = 16;
    bool spp_given = false;
    double time_budget = 0.0;
    std::string reference;
    std::string out = "out/render.png";
    float exposure = 0.0f;
    ToneMap tone_map = ToneMap::clamp;
    int jpeg_quality = 90;
    ExrPixel exr_pixel = ExrPixel::single;
    std::vector<float> sky;
    CameraOptions camera;
    RenderOptions() { settings.samples_per_pass = 0; }
    bool time_budget_only() const { return time_budget > 0.0 && !spp_given; }
};

/// Bytes per pixel the command holds besides the renderer's: the reference, and the larger of
/// the output (the film's mean, tone-mapped in place for 8-bit formats, then the encoder's
/// buffers) and the --stats trace of one ray per pixel.
std::uint64_t command_bytes_per_pixel(const RenderOptions& o) {
    const std::uint64_t image = sizeof(glm::vec3) + save_image_bytes_per_pixel(image_format(o.out));
    const std::uint64_t stats = o.common.stats_path.empty() ? 0 : trace_bytes_per_ray(true);
    const std::uint64_t reference = o.reference.empty() ? 0 : sizeof(glm::vec3);
    return reference + std::max(image, stats);
}

int render_frame(const RenderOptions& o, const FrameJob& frame, const RenderSettings& settings,
                 const std::optional<Image>& reference, AnimatedScene& animated, Tracer& tracer,
                 Renderer& renderer, const Camera& camera);

/// What an interrupted render wrote: `spp` samples per pixel of `frames[index]` (0: nothing),
/// and the frames after it not rendered.
std::string interrupted_report(const RenderOptions& o, const std::vector<FrameJob>& frames,
                               std::size_t index, int spp) {
    const FrameJob& frame = frames[index];
    std::string report = frames.size() > 1 ? "frame " + std::to_string(frame.index) + ": " : "";
    if (spp == 0)
        report += "no pass completed, nothing written";
    else
        report += "wrote " + frame.out + " with " + std::to_string(spp) +
                  (o.time_budget_only() ? "" : " of " + std::to_string(o.spp)) +
                  " samples per pixel";
    if (const std::size_t left = frames.size() - index - 1)
        report +=
            "; " + std::to_string(left) + " later frame" + (left > 1 ? "s" : "") + " not rendered";
    return report;
}

void run(RenderOptions o) {
    catch_interrupts();  // until the render starts, Ctrl-C exits at once
    take_animation_file(o.common.scene, o.animation);
    const auto threads = apply_thread_limit(o.common);
    // The flags' values and combinations first: usage errors, before any work.
    std::vector<FrameJob> frames;
    RenderSettings settings = o.settings;
    check_flags([&] {
        image_format(o.out);  // an unknown extension
        // An animation (animation_options.h) renders each frame to its own file; a still
        // scene is one frame at t = 0.
        frames = frame_jobs(o.animation, o.out);
        if (frames.size() > 1 && (!o.reference.empty() || !o.common.stats_path.empty()))
            throw InputError(
                "--reference and --stats are for one image: give --time, not --frames");
        settings.samples_per_pass =
            resolve_samples_per_pass(settings.samples_per_pass, settings.width, settings.height,
                                     o.time_budget_only() ? 0 : o.spp);
        // Motion blur renders each pass at its own time of the shutter: passes of one sample.
        if (o.animation.shutter > 0.0) settings.samples_per_pass = 1;
        if (!o.sky.empty()) settings.sky = {o.sky[0], o.sky[1], o.sky[2]};
        validate(settings);
        validate_exposure(o.exposure);
        if (!(o.time_budget >= 0.0) || !std::isfinite(o.time_budget))
            throw InputError("--time-budget must be a finite number of seconds >= 0");
    });
    std::vector<NamedPath> outputs;
    for (const FrameJob& frame : frames) outputs.push_back({"--out", frame.out});
    outputs.push_back({"--stats", o.common.stats_path});
    check_distinct_files(outputs, {{"--reference", o.reference},
                                   {"--scene", o.common.scene},
                                   {"--animate", o.animation.animate}});
    check_render_memory(settings, command_bytes_per_pixel(o));
    const auto tracer = make_tracer(o.common);  // rejects bad parameters early
    std::optional<Image> reference;
    if (!o.reference.empty()) reference = load_image(o.reference);
    if (reference && (reference->width != settings.width || reference->height != settings.height))
        throw InputError(o.reference + ": the reference is " + std::to_string(reference->width) +
                         "x" + std::to_string(reference->height) + ", the render " +
                         std::to_string(settings.width) + "x" + std::to_string(settings.height));
    // Where the images and statistics go is checked before the render, not after it.
    for (const FrameJob& frame : frames) create_parent_folders(frame.out);
    check_writable(o.common.stats_path, "--stats");
    AnimatedScene animated = load_animated_verbose(o.common.scene, o.animation);
    check_outputs_spare_scene(outputs, animated.scene);
    const Camera camera = choose_camera(animated.scene, o.camera);
    Renderer renderer(animated.scene, *tracer, camera, settings);
    for (const std::string& note : renderer.notes()) std::cerr << "edacrt: note: " << note << "\n";
    // Ctrl-C from here stops at the next batch and keeps the passes completed.
    keep_work_on_interrupt();
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const int spp =
            render_frame(o, frames[i], settings, reference, animated, *tracer, renderer, camera);
        if (interrupted()) throw Interrupted(interrupted_report(o, frames, i, spp));
    }
}

/// Renders one image of `frame` with `renderer`: the animation's geometry at the frame's time,
/// taken by the tracer as --update says, then the passes, the image and the statistics.
/// Returns the samples per pixel written: fewer when interrupted (none: nothing written).
int render_frame(const RenderOptions& o, const FrameJob& frame, const RenderSettings& settings,
                 const std::optional<Image>& reference, AnimatedScene& animated, Tracer& tracer,
                 Renderer& renderer, const Camera& camera) {
    const Scene& scene = animated.scene;
    if (animated.animation) animated.animation->frame(frame.time, animated.scene);
    const SceneUpdate how = o.animation.update;
    const UpdateStats update = tracer.update_scene(scene, how);
    const double prepare_seconds = update.seconds;
    renderer.scene_changed(scene);
    // Motion blur: each pass at its own time of the shutter (render/sampler.h).
    const bool blur = animated.animation && o.animation.shutter > 0.0;
    double scene_time = frame.time;
    std::chrono::steady_clock::time_point start;
    // With only a time budget, render until it is spent.
    const int spp = o.time_budget_only() ? 1 << 20 : o.spp;
    TraceDetail detail;
    nlohmann::json passes = nlohmann::json::array();
    double elapsed = 0.0;  // rendering only: comparing with the reference is not counted
    Progress progress(progress_style(o.common.quiet), "render", Progress::Unit::samples);
    const std::string of_spp = o.time_budget_only() ? "" : "/" + std::to_string(spp);
    progress.begin("first pass");
    while (renderer.film().passes() < spp && (o.time_budget == 0.0 || elapsed < o.time_budget) &&
           !interrupted()) {
        start = std::chrono::steady_clock::now();
        const double t =
            shutter_time(frame.time, o.animation.shutter, std::uint32_t(renderer.film().passes()));
        if (blur && t != scene_time) {
            animated.animation->frame(t, animated.scene);
            tracer.update_scene(scene, how);
            renderer.scene_changed(scene, true);
            scene_time = t;
        }
        // An interrupted pass leaves the film as the last complete pass left it.
        if (!renderer.render_pass(
                &interrupted(), nullptr,
                std::min(settings.samples_per_pass, spp - renderer.film().passes())))
            break;
        elapsed += seconds_since(start);
        const int done = renderer.film().passes();
        const double fraction =
            std::max(double(done) / spp, o.time_budget > 0.0 ? elapsed / o.time_budget : 0.0);
        const PassStats& sofar = renderer.total();
        char rays[32];
        std::snprintf(rays, sizeof rays, "%.2f Mrays/s",
                      sofar.trace_seconds > 0.0
                          ? double(sofar.trace.rays) / sofar.trace_seconds * 1e-6
                          : 0.0);
        progress.step(fraction, done, std::to_string(done) + of_spp + " spp", rays);
        nlohmann::json pass = {{"spp", renderer.film().passes()},
                               {"seconds", elapsed},
                               {"trace_seconds", renderer.total().trace_seconds},
                               {"rays", renderer.total().trace.rays}};
        if (reference) {
            const ImageError error = compare_images(renderer.film().mean(), *reference);
            pass["rmse"] = error.rmse;
            pass["relative_mse"] = error.relative_mse;
            std::ostringstream line;
            line << "spp " << renderer.film().passes() << "  " << elapsed << " s  rmse "
                 << error.rmse << "  relMSE " << error.relative_mse;
            progress.print(std::cout, line.str());
        }
        passes.push_back(pass);
    }
    progress.finish();
    const double render_seconds = elapsed;
    if (renderer.film().passes() == 0) return 0;  // interrupted before the first pass ended

    // A temporary only: the image is gone before the statistics trace below.
    const std::string method(enum_name(kMethods, tracer.method()));
    const std::string integrator(enum_name(kIntegrators, settings.integrator));
    save_image(
        frame.out, renderer.film().mean(),
        {o.exposure, o.tone_map, o.jpeg_quality, o.exr_pixel,
         render_metadata({"edacrt render", scene.source, method, integrator,
                          renderer.film().passes(), settings.seed, render_seconds, camera})});

    const PassStats& total = renderer.total();
    const double mrays = double(total.trace.rays) / total.trace_seconds * 1e-6;
    if (animated.animation)
        std::cout << "frame " << frame.index << " (t = " << frame.time << " s): " << method << " "
                  << enum_name(kUpdateWorks, update.work) << " in " << update.seconds * 1e3
                  << " ms; ";
    std::cout << "rendered " << settings.width << "x" << settings.height << " at "
              << renderer.film().passes() << " spp (" << integrator << ") with " << method << " in "
              << render_seconds << " s: " << total.trace.rays << " rays in " << total.batches
              << " batches traced in " << total.trace_seconds << " s (" << mrays
              << " Mrays/s), written to " << frame.out << "\n";
    if (total.dropped_samples)
        std::cerr << "edacrt: warning: " << total.dropped_samples
                  << " non-finite samples were replaced by black\n";

    nlohmann::json stats = {
        {"command", "render"},
        {"scene", scene.source},
        {"triangles", scene.triangle_count()},
        {"method", method},
        {"integrator", integrator},
        {"width", settings.width},
        {"height", settings.height},
        {"spp", renderer.film().passes()},
        {"seed", settings.seed},
        {"rays", total.trace.rays},
        {"batches", total.batches},
        {"ray_box_tests", total.trace.ray_box_tests},
        {"ray_triangle_tests", total.trace.ray_triangle_tests},
        {"prepare_seconds", prepare_seconds},
        {"scene_update",
         {{"mode", enum_name(kSceneUpdates, how)}, {"work", enum_name(kUpdateWorks, update.work)}}},
        {"trace_seconds", total.trace_seconds},
        {"render_seconds", render_seconds},
        {"mrays_per_second", mrays},
        {"dropped_samples", total.dropped_samples},
        {"passes", passes}};
    // Where the trace time went, batch by batch kind (camera, bounce:N, shadow:N, ao).
    for (const BatchTimes& b : total.by_batch)
        stats["batch_times"].push_back({{"batch", batch_name(b.id)},
                                        {"batches", b.batches},
                                        {"rays", b.rays},
                                        {"seconds", b.seconds}});
    if (tracer.method() == Method::embree)
        stats["embree_mode"] = enum_name(kEmbreeModes, o.common.embree_mode);
    if (animated.animation) {
        stats["animation"] = animated.animation->spec();
        stats["time"] = frame.time;
    }
    if (interrupted()) {
        stats["interrupted"] = true;  // the user is waiting: no extra trace for the detail
    } else {
        if (!o.common.stats_path.empty()) {
            const std::vector<Ray> rays =
                PinholeProjection(camera, settings.width, settings.height).pixel_centre_rays();
            std::vector<Hit> hits(rays.size());
            tracer.trace(rays, hits, Query::closest, &detail);
        }
        stats["detail"] = stats_json(detail);
        stats["detail"]["from"] = "an extra, untimed trace of one camera ray per pixel centre";
    }
    write_stats(o.common, stats);
    return renderer.film().passes();
}

}  // namespace

std::function<void()> add_render_command(CLI::App& app) {
    auto options = std::make_shared<RenderOptions>();
    RenderOptions& o = *options;
    CLI::App* command = app.add_subcommand(
        "render",
        "Render progressively (--samples-per-pass samples per pixel per pass) to an image: "
        "PNG or JPEG (tone-mapped), HDR, PFM or OpenEXR (linear).\nExample: edacrt render "
        "--scene assets/cornell-box/CornellBox-Original.obj --spp 64 --out out/cornell.exr");
    add_common_options(*command, o.common);
    RenderSettings& s = o.settings;
    flags::add_image_size_options(*command, s.width, s.height);
    flags::add_enum_option(*command, "--integrator", s.integrator, kIntegrators, "integrator");
    flags::add_enum_option(*command, "--primary", s.primary, kPrimaryShadings, "primary shading");
    command
        ->add_option_function<int>(
            "--spp",
            [&o](int spp) {
                o.spp = spp;
                o.spp_given = true;
            },
            "samples per pixel (default 16, or unlimited with --time-budget)")
        ->check(CLI::Range(1, 1 << 20));
    command->add_option("--time-budget", o.time_budget,
                        "stop after this many seconds of rendering (0: no limit)");
    command->add_option("--reference", o.reference,
                        "an image of the same size (" + enum_names(kImageFormats) +
                            "): report the error after every pass");
    command->add_option("--max-depth", s.max_depth, "path: bounces")->capture_default_str();
    command->add_option("--roulette-depth", s.roulette_depth, "path: Russian roulette from here")
        ->capture_default_str();
    command->add_option("--ao-samples", s.ao_samples, "ao: rays per hit")->capture_default_str();
    command->add_option("--ao-distance", s.ao_distance, "ao: max distance (0: scene size / 4)")
        ->capture_default_str();
    command->add_option("--sky", o.sky, "sky radiance R,G,B (scenes without emitters)")
        ->delimiter(',')
        ->expected(3);
    command
        ->add_option("--samples-per-pass", s.samples_per_pass,
                     "samples per pixel traced together in one pass (at most --spp); 0: about "
                     "1M paths per pass, at least 4 samples (4 with --time-budget alone)")
        ->capture_default_str();
    command
        ->add_option("--wavefront-paths", s.wavefront_paths,
                     "paths per wavefront (0: the whole pass, within 1 GiB of wavefront state)")
        ->check(flags::whole_number())
        ->capture_default_str();
    command->add_option("--seed", s.seed, "sample seed")->capture_default_str();
    command->add_option("--exposure", o.exposure, "PNG, JPEG: exposure in stops")
        ->capture_default_str();
    flags::add_enum_option(*command, "--tone-map", o.tone_map, kToneMaps,
                           "PNG, JPEG: how radiance becomes display values");
    command->add_option("--jpeg-quality", o.jpeg_quality, "JPEG: quality")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    flags::add_enum_option(*command, "--exr-pixel", o.exr_pixel, kExrPixels, "EXR: pixel type");
    command
        ->add_option("--out", o.out,
                     flags::enum_option_help("output image; its extension chooses the format",
                                             kImageFormats))
        ->capture_default_str();
    flags::add_camera_options(*command, o.camera);
    add_animation_options(*command, o.animation);
    return [options] { run(*options); };
}

}  // namespace edacrt::cli
