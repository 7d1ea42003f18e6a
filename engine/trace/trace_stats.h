#pragma once
// What a trace call did: totals for every call, and (on request) per recursion level and per
// ray, for the viewer's tables and heat-maps and for the benchmarks.
#include <cstdint>
#include <vector>

#include "geometry/aabb.h"

namespace edacrt {

/// Totals of one trace call.
struct TraceStats {
    std::uint64_t rays = 0;
    std::uint64_t ray_box_tests = 0;
    std::uint64_t ray_triangle_tests = 0;

    TraceStats& operator+=(const TraceStats& o) {
        rays += o.rays;
        ray_box_tests += o.ray_box_tests;
        ray_triangle_tests += o.ray_triangle_tests;
        return *this;
    }
};

/// One level of a divide-and-conquer recursion (level 0 is the scene box).
struct LevelStats {
    std::uint64_t nodes = 0;
    std::uint64_t leaves = 0;
    std::uint64_t rays_in = 0;          // rays entering the level's nodes
    std::uint64_t rays_passed = 0;      // rays passed down to children (after filtering or not)
    std::uint64_t filters_done = 0;     // child ray sets filtered...
    std::uint64_t filters_skipped = 0;  // ...or passed down unfiltered (filter skipping)
    std::uint64_t triangles = 0;        // summed over the level's nodes
    std::uint64_t ray_box_tests = 0;    // filtering and sampling
    std::uint64_t ray_triangle_tests = 0;
    std::uint64_t sampled_rays = 0;
    std::uint64_t candidate_splits = 0;
    std::uint64_t order_hits = 0;    // rays whose final hit lay in the child visited first...
    std::uint64_t order_misses = 0;  // ...or in the one visited second
    double seconds = 0.0;            // thread time spent in the level's own work

    LevelStats& operator+=(const LevelStats& o) {
        nodes += o.nodes;
        leaves += o.leaves;
        rays_in += o.rays_in;
        rays_passed += o.rays_passed;
        filters_done += o.filters_done;
        filters_skipped += o.filters_skipped;
        triangles += o.triangles;
        ray_box_tests += o.ray_box_tests;
        ray_triangle_tests += o.ray_triangle_tests;
        sampled_rays += o.sampled_rays;
        candidate_splits += o.candidate_splits;
        order_hits += o.order_hits;
        order_misses += o.order_misses;
        seconds += o.seconds;
        return *this;
    }
};

/// What one ray cost; indexed like the rays of the batch (so, for camera rays, a pixel).
struct RayStats {
    std::uint32_t ray_box_tests = 0;
    std::uint32_t ray_triangle_tests = 0;
    std::uint16_t deepest_level = 0;  // of the recursion nodes the ray entered
    std::uint16_t order_misses = 0;   // levels where the final hit was in the second child
};

/// A candidate split of a recorded node: bins 0..j left, the rest right.
struct CandidateSplit {
    Aabb left, right;
    std::uint32_t left_triangles = 0, right_triangles = 0;
    float alpha_left = 0.0f, alpha_right = 0.0f;  // sampled hit ratios (or area ratios)
    float cost = 0.0f;                            // C_T + C_I (a_L N_L + a_R N_R); inf if empty
};

/// One node of a recorded recursion (TraceDetail::max_nodes > 0).
struct NodeRecord {
    std::int32_t parent = -1;
    std::int32_t children[2] = {-1, -1};  // left, right; -1 when not entered or not recorded
    std::uint16_t depth = 0;
    Aabb box;
    std::uint32_t rays = 0, triangles = 0;
    bool leaf = true;
    float leaf_cost = 0.0f;    // C_I x triangles per ray
    int axis = -1;             // of the binning
    std::int32_t chosen = -1;  // index into candidates; -1 for a leaf
    bool left_first = true;
    bool filter_skipped[2] = {false, false};
    std::uint32_t rays_passed[2] = {0, 0};
    std::vector<CandidateSplit> candidates;
};

/// A node the followed ray (TraceDetail::follow_ray) entered.
struct RayVisit {
    std::int32_t node = -1;  // into TraceDetail::nodes (-1 past max_nodes)
    std::uint16_t depth = 0;
    bool leaf = false;
    bool passed[2] = {false, false};  // handed to the left / right child
    bool first_side_right = false;    // the node visited its right child first
    bool hit_here = false;            // a leaf where the ray's closest hit so far changed
};

/// Detailed statistics of one trace call. Tracers without a recursion leave `levels` empty.
struct TraceDetail {
    std::vector<LevelStats> levels;
    std::vector<RayStats> rays;

    // Optional recordings of the divide-and-conquer tracers (inputs first):
    std::size_t max_nodes = 0;     // record up to this many nodes of the recursion
    std::int64_t follow_ray = -1;  // record the path of this ray through the recursion
    std::vector<NodeRecord> nodes;
    std::vector<RayVisit> follow;
};

}  // namespace edacrt
