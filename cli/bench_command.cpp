// edacrt bench: its flags; the harness is bench_harness.h.
#include <memory>

#include "bench_harness.h"
#include "bench_scenes.h"
#include "commands.h"
#include "enum_flags.h"
#include "progress.h"

namespace edacrt::cli {

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
    command->add_option("--scene", o.scenes, bench_scene_help());
    command->add_option("--sets", o.sets, flags::enum_option_help("ray sets", kRaySetKinds))
        ->delimiter(',')
        ->capture_default_str();
    command->add_option("--spp", o.spp, "samples per pixel of the camera sets, one set each")
        ->delimiter(',')
        ->check(CLI::Range(1, 1024))
        ->capture_default_str();
    command
        ->add_option(
            "--methods", o.methods,
            "methods: " + enum_names(kMethods) +
                " (embree: all three modes, the fastest is the ratio base; naive is "
                "slow); a method with settings of its own is METHOD:KEY=VALUE[:...], "
                "e.g. dacrt:presplit=0:second-child=after-first (edacrt, dacrt: the "
                "EDACRT parameters by their edacrt trace flag names, preset=NAME first; bvh: bins, "
                "max-leaf, c-t)")
        ->delimiter(',')
        ->capture_default_str();
    command->add_option("--width", o.width, "pixels per row")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    command->add_option("--height", o.height, "rows")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    command
        ->add_option("--repeat", o.repeat,
                     "frames per method and set (median and min); still frame r draws EDACRT's ray "
                     "samples with sampling seed S + r")
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
                   "animate the scenes (default: " + bench_scene_list_text("bench_dynamic") +
                       ") and time every method frame by frame on camera rays: update (bvh and "
                       "embree: rebuild, refit; embree: dynamic; edacrt, dacrt: none) + trace, "
                       "and a sweep of rays per triangle")
        ->excludes(write_rays)  // its frames are camera rays made per frame
        ->group(dynamic);
    command->add_option("--animate", o.animation, "the animation (see render --help)")
        ->capture_default_str()
        ->group(dynamic);
    command->add_option("--frames", o.frames, "timed frames per set (medians)")
        ->capture_default_str()
        ->group(dynamic);
    command
        ->add_option("--rays-per-triangle", o.rays_per_triangle,
                     "the sweep: 1-spp camera sets of these many rays per triangle")
        ->capture_default_str()
        ->delimiter(',')
        ->group(dynamic);
    return [options] { run_bench(*options); };
}

}  // namespace edacrt::cli
