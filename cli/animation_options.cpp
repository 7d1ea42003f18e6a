#include "animation_options.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <iostream>
#include <utility>

#include "common_options.h"
#include "enum_flags.h"
#include "util/error.h"
#include "util/frame_pattern.h"
#include "util/printable.h"

namespace edacrt::cli {
namespace {

constexpr std::int64_t kMaxFrames = 1'000'000;

std::int64_t frame_number(std::string_view text, const std::string& flag) {
    std::int64_t value = -1;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < 0 || value > kMaxFrames)
        throw InputError("--frames " + flag + ": frame numbers are integers from 0 to " +
                         std::to_string(kMaxFrames));
    return value;
}

}  // namespace

std::string AnimationOptions::spec() const {
    if (!animate.empty() && !sequence.empty())
        throw InputError("--animate and --sequence both name an animation: give one");
    return sequence.empty() ? animate : "sequence:pattern=" + sequence;
}

void take_animation_file(std::string& scene, AnimationOptions& o) {
    if (o.animate.empty() && o.sequence.empty() && is_animation_file(scene))
        o.animate = std::exchange(scene, {});
}

void add_animation_options(CLI::App& command, AnimationOptions& o) {
    command.get_option("--scene")->required(false);
    const std::string group = "Animation";
    command.add_option("--animate", o.animate, "animate the scene:\n" + animation_help())
        ->group(group);
    command
        .add_option("--sequence", o.sequence,
                    "OBJ key frames, e.g. 'frames/name_%04d.obj' (the same as --animate "
                    "sequence:pattern=...), instead of --scene")
        ->group(group);
    command.add_option("--time", o.time, "render the animation at this time in seconds")
        ->group(group);
    command
        .add_option("--frames", o.frames,
                    "render frames A to B (inclusive) of the animation, frame k at k / --fps "
                    "seconds, to --out with %04d for the frame number")
        ->group(group);
    command.add_option("--fps", o.fps, "frames per second of --frames (0.001 to 10000)")
        ->capture_default_str()
        ->group(group);
    flags::add_enum_option(command, "--update", o.update, kSceneUpdates,
                           "how the tracer takes each frame")
        ->group(group);
    command
        .add_option("--shutter", o.shutter,
                    "motion blur: seconds the shutter stays open around each frame's time; the "
                    "passes are rendered at times spread over it and averaged (0: none)")
        ->capture_default_str()
        ->group(group);
}

std::vector<FrameJob> frame_jobs(const AnimationOptions& o, const std::string& out) {
    if (!(o.shutter >= 0.0 && o.shutter <= 1e6))
        throw InputError("--shutter must be a number of seconds from 0 to 1e6");
    if (o.spec().empty()) {  // a still scene has one moment
        const char* flag = !o.frames.empty() ? "--frames" : o.time ? "--time" : nullptr;
        if (o.shutter > 0.0) flag = "--shutter";
        if (flag)
            throw InputError(std::string(flag) +
                             " is for an animation: give --animate or --sequence (or an "
                             "animation file as --scene)");
    }
    if (o.frames.empty()) {
        const double t = o.time.value_or(0.0);
        if (!std::isfinite(t)) throw InputError("--time must be a finite number of seconds");
        if (FramePattern::has_conversion(out))
            throw InputError("--out " + out +
                             " has a frame number but one image is rendered: "
                             "give --frames A:B, or no % in --out");
        return {{0, t, FramePattern::literal(out, "--out")}};
    }
    if (o.time) throw InputError("--time and --frames both choose what to render: give one");
    if (!(o.fps >= 1e-3 && o.fps <= 1e4))
        throw InputError("--fps must be a number from 0.001 to 10000");
    const std::size_t colon = o.frames.find(':');
    if (colon == std::string::npos)
        throw InputError("--frames " + o.frames + ": expected A:B, e.g. 0:47");
    const std::int64_t first = frame_number(std::string_view(o.frames).substr(0, colon), o.frames);
    const std::int64_t last = frame_number(std::string_view(o.frames).substr(colon + 1), o.frames);
    if (last < first)
        throw InputError("--frames " + o.frames + ": the last frame is before the first");
    const FramePattern pattern(out, "--out");
    std::vector<FrameJob> jobs;
    for (std::int64_t k = first; k <= last; ++k)
        jobs.push_back({k, double(k) / o.fps, pattern.path(k).string()});
    return jobs;
}

AnimatedScene load_animated_verbose(const std::string& scene, const AnimationOptions& o) {
    const std::string spec = o.spec();
    if (spec.empty()) {
        if (scene.empty())
            throw UsageError("no scene: give --scene, or --animate FILE.json or --sequence");
        return {load_scene_verbose(scene), nullptr};
    }
    const auto start = std::chrono::steady_clock::now();
    AnimatedScene animated = load_animated_scene(scene, spec);
    for (const std::string& warning : animated.scene.warnings)
        std::cerr << "edacrt: warning: " << printable(warning) << "\n";
    std::cerr << "loaded " << printable(animated.scene.source) << ": "
              << animated.scene.triangle_count() << " triangles, "
              << animated.scene.materials.size() << " materials, animated by "
              << animated.animation->spec() << " (" << animated.animation->duration() << " s) in "
              << seconds_since(start) << " s\n";
    return animated;
}

}  // namespace edacrt::cli
