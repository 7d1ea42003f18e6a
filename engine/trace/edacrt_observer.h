#pragma once
// The statistics of the EDACRT recursion, hooked in from outside (the recursion calls these
// hooks; NullObserver in edacrt_recursion.h has them empty). Fills a TraceDetail: per level,
// per ray, recorded nodes and the path of one followed ray. Hooks run on the recursion's
// thread, except leaf_ray() and hit(), which large leaves call from worker threads and which
// touch only the ray's own entries.
#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

#include "trace/edacrt_recursion.h"
#include "trace/trace_stats.h"

namespace edacrt {

class RecordingObserver {
  public:
    /// Its hooks keep a path and a parent between calls: subtrees must run in order.
    static constexpr bool kConcurrent = false;

    /// `cost_intersect` (C_I) prices the recorded nodes' leaf cost.
    RecordingObserver(TraceDetail& detail, const RayBatch& batch, std::size_t ray_count,
                      float cost_intersect);

    struct Visit {
        std::int32_t node = -1;      // recorded node
        std::int64_t followed = -1;  // index of the followed ray's visit
        Hit before;                  // the followed ray's hit when it entered a leaf
        int depth = 0;
        int children = 0;  // child ray sets given so far: 3 when the second child was split
    };

    /// Adds the time until its end to a phase of a level.
    class Timer {
      public:
        Timer(RecordingObserver& observer, Phase phase, int depth)
            : observer_(observer), phase_(phase), depth_(depth) {}
        Timer(const Timer&) = delete;
        ~Timer();

      private:
        RecordingObserver& observer_;
        Phase phase_;
        int depth_;
        std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    };

    /// The root filter: `entered` of `rays` rays hit the scene box.
    void root(std::uint32_t* ids, std::size_t rays, std::size_t entered, double seconds);

    Visit enter(const Node& node);
    Timer time(Phase phase, int depth) { return Timer(*this, phase, depth); }
    void sampled(const Node& node, std::uint32_t samples, std::uint64_t tests);
    void sampled_ray(std::uint32_t ray, std::uint32_t tests) {
        detail_.rays[ray].ray_box_tests += tests;
    }
    void candidate(Visit& visit, const CandidateSplit& candidate);
    /// Before the children: measures the true hit ratios and which rays hit both children.
    void split(Visit& visit, const Node& node, const Split& split);
    /// `child` holds the rays passed to side `side`; when filtered, the rejected ones follow
    /// them in the node's range of the stream.
    void child(Visit& visit, const Node& node, const Split& split, int side, int visit_index,
               bool skipped, const Node& child);
    void leaf_ray(std::uint32_t ray, std::uint32_t tests) {
        detail_.rays[ray].ray_triangle_tests += tests;
    }
    void hit(std::uint32_t ray, const Node& node) {
        hit_path_[ray] = node.path;
        hit_depth_[ray] = std::uint16_t(std::min(node.depth, kPathLevels));
        both_at_hit_[ray] = both_[ray];
        if (!detail_.hit_node.empty()) detail_.hit_node[ray] = entered_record_;
    }
    void leaf(Visit& visit, const Node& node, std::uint64_t tests);
    /// The node runs its second child as if beside the first (speculation).
    void speculated(const Node& node) { ++level(node.depth).speculated; }
    /// What the observer keeps of a ray's hit, so that a hit the recursion then drops (the
    /// farther of a speculating node's two) can be taken back.
    struct HitState {
        std::uint64_t path = 0, both = 0;
        std::uint16_t depth = 0;
        std::int32_t node = -1;
    };
    HitState hit_state(std::uint32_t ray) const {
        return {hit_path_[ray], both_at_hit_[ray], hit_depth_[ray],
                detail_.hit_node.empty() ? -1 : detail_.hit_node[ray]};
    }
    void restore_hit(std::uint32_t ray, const HitState& state) {
        hit_path_[ray] = state.path;
        both_at_hit_[ray] = state.both;
        hit_depth_[ray] = state.depth;
        if (!detail_.hit_node.empty()) detail_.hit_node[ray] = state.node;
    }

    /// Order statistics from each ray's final hit; call once after the recursion.
    void finish(std::span<const Hit> hits);

  private:
    LevelStats& level(int depth);
    bool follows(const Node& node) const;

    TraceDetail& detail_;
    const RayBatch& batch_;
    float cost_intersect_;
    // Per ray: the path of the leaf that produced its hit (bit d: second-visited child at
    // depth d), that leaf's depth, and bit d set when the ray hit both children's boxes at its
    // depth-d ancestor (both_ is the current recursion path's, both_at_hit_ the hit's);
    // second_ bit d: the ray reached the box of that ancestor's second child on entering it.
    std::vector<std::uint64_t> hit_path_, both_, both_at_hit_, second_;
    std::vector<std::uint16_t> hit_depth_;
    // The recorded parent and side of the next node entered (set by child()).
    std::int32_t next_parent_ = -1;
    int next_side_ = 0;
    // The record of the node entered last: a leaf's hits are found before another is entered
    // (this observer is not concurrent).
    std::int32_t entered_record_ = -1;
};

}  // namespace edacrt
