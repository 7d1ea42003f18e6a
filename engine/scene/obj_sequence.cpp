#include "scene/obj_sequence.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <vector>

#include "scene/obj_loader.h"
#include "util/error.h"
#include "util/frame_pattern.h"
#include "util/input_file.h"
#include "util/spec_options.h"

namespace edacrt {
namespace {

/// The frame numbers of the files that `pattern` names, ascending without a gap.
std::vector<std::int64_t> find_frames(const FramePattern& pattern) {
    const std::filesystem::path directory = pattern.directory();
    std::error_code error;
    std::filesystem::directory_iterator it(directory, error);
    if (error)
        throw InputError("sequence " + pattern.pattern() + ": cannot list " + directory.string() +
                         ": " + error.message());
    std::vector<std::int64_t> frames;
    // Error codes throughout: a symlink loop or a vanished file is bad input, not a bug.
    for (; !error && it != std::filesystem::directory_iterator(); it.increment(error)) {
        const auto index = pattern.match(it->path().filename().string());
        if (!index) continue;
        const bool regular = it->is_regular_file(error);
        if (error)
            throw InputError("sequence " + pattern.pattern() + ": cannot read " +
                             it->path().string() + " in " + directory.string() + ": " +
                             error.message());
        // Skipped, a FIFO or device shortened the sequence or read as a missing frame: the
        // check every reader makes refuses it by name.
        if (!regular)
            check_input_file(it->path(), "key frame", std::numeric_limits<std::uint64_t>::max());
        frames.push_back(*index);
    }
    if (error)
        throw InputError("sequence " + pattern.pattern() + ": cannot list " + directory.string() +
                         ": " + error.message());
    if (frames.empty())
        throw InputError("sequence " + pattern.pattern() + ": no file in " + directory.string() +
                         " matches it");
    std::sort(frames.begin(), frames.end());
    for (std::size_t i = 1; i < frames.size(); ++i)
        if (frames[i] != frames[i - 1] + 1)
            throw InputError("sequence " + pattern.pattern() + ": key frame " +
                             pattern.path(frames[i - 1] + 1).string() +
                             " is missing (the files run from " +
                             pattern.path(frames.front()).string() + " to " +
                             pattern.path(frames.back()).string() + ")");
    return frames;
}

class ObjSequence final : public Animation {
  public:
    ObjSequence(std::string spec, const Scene& first, FramePattern pattern,
                std::int64_t first_frame, std::int64_t keys, double fps)
        : Animation(std::move(spec), first),
          pattern_(std::move(pattern)),
          first_frame_(first_frame),
          keys_(keys),
          fps_(fps) {
        slots_[0] = {0, first.positions, first.normals};
    }

    double duration() const override { return double(keys_ - 1) / fps_; }

  private:
    struct Slot {
        std::int64_t key = -1;
        std::vector<glm::vec3> positions, normals;
    };

    void write_frame(double t, Scene& scene) override {
        const double u = std::clamp(t * fps_, 0.0, double(keys_ - 1));
        const auto k = std::int64_t(std::floor(u));
        const float w = float(u - double(k));
        if (w == 0.0f) {
            const Slot& a = slot(k, -1, scene);
            std::copy(a.positions.begin(), a.positions.end(), scene.positions.begin());
            std::copy(a.normals.begin(), a.normals.end(), scene.normals.begin());
            return;
        }
        const Slot& a = slot(k, k + 1, scene);
        const Slot& b = slot(k + 1, k, scene);
        for (std::size_t v = 0; v < scene.positions.size(); ++v)
            scene.positions[v] = a.positions[v] + (b.positions[v] - a.positions[v]) * w;
        for (std::size_t n = 0; n < scene.normals.size(); ++n) {
            const glm::vec3 mix = a.normals[n] + (b.normals[n] - a.normals[n]) * w;
            const float length = glm::length(mix);
            // Opposite normals cancel half way: take the nearer key's.
            scene.normals[n] = length > 0.0f && std::isfinite(length)
                                   ? mix / length
                                   : (w < 0.5f ? a.normals[n] : b.normals[n]);
        }
    }

    /// Key `key`, read into the slot that does not hold `keep` unless already held.
    const Slot& slot(std::int64_t key, std::int64_t keep, const Scene& scene) {
        for (const Slot& s : slots_)
            if (s.key == key) return s;
        Slot& s = slots_[slots_[0].key == keep ? 1 : 0];
        s.key = -1;  // until it is read and checked
        const std::filesystem::path path = pattern_.path(first_frame_ + key);
        Scene frame = load_obj(path);
        const std::string first = pattern_.path(first_frame_).string();
        const auto differ = [&](const std::string& what) {
            throw InputError(path.string() + ": " + what + " than the first key frame " + first +
                             "; a sequence's key frames must have the same triangles");
        };
        if (frame.triangles.size() != scene.triangles.size())
            differ(std::to_string(frame.triangles.size()) + " triangles, other");
        if (frame.positions.size() != scene.positions.size())
            differ(std::to_string(frame.positions.size()) + " vertices, other");
        const auto mismatch =
            std::mismatch(frame.triangles.begin(), frame.triangles.end(), scene.triangles.begin());
        if (mismatch.first != frame.triangles.end())
            differ("triangle " + std::to_string(mismatch.first - frame.triangles.begin()) +
                   " has other corners");
        if (frame.normals.size() != scene.normals.size() ||
            frame.triangle_normals != scene.triangle_normals)
            differ("other shading normals");
        s.positions = std::move(frame.positions);
        s.normals = std::move(frame.normals);
        s.key = key;
        return s;
    }

    FramePattern pattern_;
    std::int64_t first_frame_, keys_;
    double fps_;
    std::array<Slot, 2> slots_;
};

}  // namespace

AnimatedScene open_obj_sequence(std::string_view spec) {
    const std::string_view body = spec.substr(std::string_view("sequence:").size());
    const std::size_t at = body.find("pattern=");
    if (at == std::string_view::npos || (at > 0 && body[at - 1] != ','))
        throw InputError(std::string(spec) +
                         ": expected sequence:[fps=F,]pattern=PATH (the pattern comes last)");
    SpecOptions options(spec, body.substr(0, at == 0 ? 0 : at - 1));
    const double fps = options.number("fps", 24.0, 1e-3, 1e4);
    options.finish();
    const std::string_view pattern_text = body.substr(at + std::string_view("pattern=").size());
    FramePattern pattern(std::string(pattern_text), "sequence pattern");
    const std::vector<std::int64_t> frames = find_frames(pattern);

    AnimatedScene out{load_obj(pattern.path(frames.front())), nullptr};
    for (std::size_t k = 1; k < frames.size(); ++k)  // key frames are read as they are shown
        out.scene.inputs.push_back(pattern.path(frames[k]).string());
    out.animation = std::make_unique<ObjSequence>(
        "sequence:fps=" + shortest_text(fps) + ",pattern=" + std::string(pattern_text), out.scene,
        std::move(pattern), frames.front(), std::int64_t(frames.size()), fps);
    out.animation->frame(0.0, out.scene);
    return out;
}

}  // namespace edacrt
