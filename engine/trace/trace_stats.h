#pragma once
// What a trace call did: totals for every call, and (on request) per recursion level and per
// ray, for the viewer's tables and heat-maps and for the benchmarks.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/aabb.h"
#include "util/enum_table.h"

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

/// Where a split node's hit ratios alpha came from.
enum class AlphaSource : std::uint8_t {
    sampled,    // the share of rays drawn at random that hit each child box
    area,       // child box area / node box area
    every_ray,  // the share of all the node's rays: exact
};
inline constexpr auto kAlphaSources =
    enum_table<AlphaSource>("alpha source", {{AlphaSource::sampled, "sampled"},
                                             {AlphaSource::area, "area"},
                                             {AlphaSource::every_ray, "every ray"}});

/// Per-node alpha errors are counted in bins of this width, [0, 0.01), [0.01, 0.02), ...
inline constexpr int kAlphaErrorBins = 100;
inline constexpr double kAlphaErrorBinWidth = 1.0 / kAlphaErrorBins;

/// One level of a divide-and-conquer recursion (level 0 is the scene box's node).
struct LevelStats {
    std::uint64_t nodes = 0;
    std::uint64_t leaves = 0;
    std::uint64_t rays_in = 0;           // rays entering the level's nodes
    std::uint64_t rays_passed = 0;       // rays passed down to children (after filtering or not)
    std::uint64_t filters_done = 0;      // child ray sets filtered...
    std::uint64_t filters_skipped = 0;   // ...or passed down unfiltered (filter skipping)
    std::uint64_t second_splits = 0;     // nodes whose second child got its rays in two parts
                                         // (SecondChild::split): one more child ray set each
    std::uint64_t speculated = 0;        // nodes whose second child ran beside the first, on a
                                         // copy of their rays (Recursion::speculates)
    std::uint64_t triangles = 0;         // summed over the level's nodes
    std::uint64_t ray_box_tests = 0;     // sample_box_tests + filter_box_tests
    std::uint64_t sample_box_tests = 0;  // sampled rays against the candidates' boxes
    std::uint64_t filter_box_tests = 0;  // rays filtered against the chosen children's boxes
    std::uint64_t ray_triangle_tests = 0;
    std::uint64_t sampled_rays = 0;
    std::uint64_t candidate_splits = 0;
    // Order quality: rays that hit both children's boxes of a node of this level and found
    // their final hit below it, by whether the hit was in the child visited first...
    std::uint64_t order_hits = 0;
    std::uint64_t order_misses = 0;  // ...or in the one visited second
    // Rays the second child's filter rejected only because their hit so far is nearer than
    // its box: what visiting the near child first bought.
    std::uint64_t culled_by_distance = 0;
    // Sampling quality, over the children of the level's splits: the estimated alpha (sampled,
    // or area ratio) against the true one, the share of the node's rays that hit the child.
    std::uint64_t alpha_children = 0;
    double alpha_estimated_sum = 0.0;
    double alpha_true_sum = 0.0;
    double alpha_error_sum = 0.0;  // of |estimated - true|
    // ...and their distribution over the children (the level means hide single nodes far off).
    std::uint64_t alpha_error_bins[kAlphaErrorBins] = {};
    double alpha_error_max = 0.0;
    std::uint64_t sampled_nodes = 0;  // nodes that sampled rays (sampled_rays of them)
    std::uint64_t alpha_sources[kAlphaSources.size()] = {};  // split nodes by AlphaSource
    // Wall time of the level's own work on the recursion's thread, by phase (sampling, binning
    // and partitioning, filtering, leaves); large nodes run their phases in parallel.
    double phase_seconds[4] = {0.0, 0.0, 0.0, 0.0};

    double seconds() const {
        return phase_seconds[0] + phase_seconds[1] + phase_seconds[2] + phase_seconds[3];
    }

    void add_alpha_error(double error) {
        ++alpha_error_bins[std::min(int(error * kAlphaErrorBins), kAlphaErrorBins - 1)];
        alpha_error_max = std::max(alpha_error_max, error);
    }

    /// The alpha error that a share q of the children do not exceed: the upper end of its bin
    /// (or the largest error, if less); 0 without children.
    double alpha_error_quantile(double q) const {
        const double rank = q * double(alpha_children);
        std::uint64_t below = 0;
        for (int b = 0; b < kAlphaErrorBins; ++b) {
            below += alpha_error_bins[b];
            if (below > 0 && double(below) >= rank)
                return std::min(double(b + 1) * kAlphaErrorBinWidth, alpha_error_max);
        }
        return alpha_error_max;
    }

    LevelStats& operator+=(const LevelStats& o) {
        nodes += o.nodes;
        leaves += o.leaves;
        rays_in += o.rays_in;
        rays_passed += o.rays_passed;
        filters_done += o.filters_done;
        second_splits += o.second_splits;
        speculated += o.speculated;
        filters_skipped += o.filters_skipped;
        triangles += o.triangles;
        ray_box_tests += o.ray_box_tests;
        sample_box_tests += o.sample_box_tests;
        filter_box_tests += o.filter_box_tests;
        ray_triangle_tests += o.ray_triangle_tests;
        sampled_rays += o.sampled_rays;
        candidate_splits += o.candidate_splits;
        order_hits += o.order_hits;
        order_misses += o.order_misses;
        culled_by_distance += o.culled_by_distance;
        alpha_children += o.alpha_children;
        alpha_estimated_sum += o.alpha_estimated_sum;
        alpha_true_sum += o.alpha_true_sum;
        alpha_error_sum += o.alpha_error_sum;
        for (int b = 0; b < kAlphaErrorBins; ++b) alpha_error_bins[b] += o.alpha_error_bins[b];
        alpha_error_max = std::max(alpha_error_max, o.alpha_error_max);
        sampled_nodes += o.sampled_nodes;
        for (std::size_t i = 0; i < kAlphaSources.size(); ++i)
            alpha_sources[i] += o.alpha_sources[i];
        for (int i = 0; i < 4; ++i) phase_seconds[i] += o.phase_seconds[i];
        return *this;
    }
};

/// The filter of the batch against the scene box, before the recursion.
struct RootStats {
    std::uint64_t rays = 0;
    std::uint64_t entered = 0;  // rays that hit the scene box: the root node's rays
    std::uint64_t box_tests = 0;
    double seconds = 0.0;

    RootStats& operator+=(const RootStats& o) {
        rays += o.rays;
        entered += o.entered;
        box_tests += o.box_tests;
        seconds += o.seconds;
        return *this;
    }
};

/// What one ray cost; indexed like the rays of the batch (so, for camera rays, a pixel).
struct RayStats {
    std::uint32_t ray_box_tests = 0;
    std::uint32_t ray_triangle_tests = 0;
    std::uint16_t deepest_level = 0;  // of the recursion nodes the ray entered
    std::uint16_t order_misses = 0;   // levels where the ray hit both children's boxes and
                                      // found its final hit in the one visited second
};

/// A candidate split of a recorded node: bins 0..j left, the rest right.
struct CandidateSplit {
    Aabb left, right;
    std::uint32_t left_triangles = 0, right_triangles = 0;
    float alpha_left = 0.0f, alpha_right = 0.0f;  // hit ratios (NodeRecord::alpha_source)
    float cost = 0.0f;                            // C_T + C_I (a_L N_L + a_R N_R); inf if empty
    float plane = 0.0f;  // on the node's axis: triangles whose centroid lies below go left
};

/// One node of a recorded recursion (TraceDetail::max_nodes > 0).
struct NodeRecord {
    std::int32_t parent = -1;
    std::int32_t children[2] = {-1, -1};  // left, right; -1 when not entered or not recorded
    // With SecondChild::split, the second child's part that took the rays which missed the
    // first child's box; children[] holds the part entered after the first child.
    std::int32_t second_early = -1;
    std::uint16_t depth = 0;
    Aabb box;
    std::uint32_t rays = 0, triangles = 0;
    bool leaf = true;
    float leaf_cost = 0.0f;    // C_I x triangles per ray
    int axis = -1;             // of the binning
    std::int32_t chosen = -1;  // index into candidates; -1 for a leaf
    bool left_first = true;
    float alpha_true[2] = {0.0f, 0.0f};  // share of the node's rays that hit each child's box
    AlphaSource alpha_source = AlphaSource::sampled;  // of the candidates' alpha
    std::uint32_t samples = 0;  // rays sampled for alpha or the order (0: none)
    bool filter_skipped[2] = {false, false};
    std::uint32_t rays_passed[2] = {0, 0};
    std::vector<CandidateSplit> candidates;
    // Where the node's `rays` ray ids start in TraceDetail::node_ray_ids; -1 past that
    // recording's budget.
    std::int64_t ray_ids = -1;

    /// |estimated - true| alpha of the chosen split's child `side` (0 left, 1 right).
    double alpha_error(int side) const {
        const CandidateSplit& c = candidates[std::size_t(chosen)];
        return std::abs(double(side == 0 ? c.alpha_left : c.alpha_right) - alpha_true[side]);
    }
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
    RootStats root;
    std::vector<LevelStats> levels;
    std::vector<RayStats> rays;

    // Optional recordings of the divide-and-conquer tracers (inputs first):
    std::size_t max_nodes = 0;     // record up to this many nodes of the recursion
    std::int64_t follow_ray = -1;  // record the path of this ray through the recursion
    std::vector<NodeRecord> nodes;
    std::vector<RayVisit> follow;
    // With recorded nodes: each node's ray ids, up to this many ids in all (the explorer tints
    // a node's pixels) ...
    std::size_t max_node_ray_ids = 0;
    std::vector<std::uint32_t> node_ray_ids;
    // ... and per ray, the recorded leaf that found its final hit (-1: none, or not recorded).
    // Nodes are recorded in the order the recursion enters them, so a prefix of the nodes
    // shows the hits found so far (the explorer's step-through).
    std::vector<std::int32_t> hit_node;
};

}  // namespace edacrt
