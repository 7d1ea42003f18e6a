#pragma once
// The animation flags of `edacrt render` (--animate, --sequence, --time, --frames, --fps,
// --update): which animation, which frames, and how the tracer takes each frame.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/animation.h"
#include "trace/tracer.h"

namespace edacrt::cli {

struct AnimationOptions {
    std::string animate;         // a spec of load_animated_scene()
    std::string sequence;        // shorthand for --animate sequence:pattern=...
    std::optional<double> time;  // seconds
    std::string frames;          // "A:B", inclusive
    double fps = 24.0;           // frame k of --frames is at t = k / fps
    SceneUpdate update = SceneUpdate::rebuild;
    double shutter = 0.0;  // seconds of motion blur around each frame's time (0: none)

    /// The animation spec the flags name; empty for a still scene.
    std::string spec() const;
};

/// An animation file given as --scene is read as --animate FILE (as the viewer reads it), when
/// no other animation is named.
void take_animation_file(std::string& scene, AnimationOptions& options);

/// Adds the flags to `command`, whose --scene becomes optional (an animation file names its
/// own geometry).
void add_animation_options(CLI::App& command, AnimationOptions& options);

/// One image to render: frame `index` at `time` seconds, written to `out`.
struct FrameJob {
    std::int64_t index;
    double time;
    std::string out;
};

/// The images to render: with --frames A:B one per frame to the pattern `out` (a %d or %0Nd,
/// util/frame_pattern.h), else one at --time (0 without it) to `out`. Throws InputError for bad
/// flags or combinations (a pattern for one image, none for several, --frames, --time or
/// --shutter without an animation).
std::vector<FrameJob> frame_jobs(const AnimationOptions& options, const std::string& out);

/// The scene, animated as the flags say, with load_scene_verbose()'s report on stderr.
AnimatedScene load_animated_verbose(const std::string& scene, const AnimationOptions& options);

}  // namespace edacrt::cli
