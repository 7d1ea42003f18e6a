#pragma once
// The EDACRT recursion (Nabata, Iwasaki, Dobashi, Nishita, "Efficient Divide-And-Conquer Ray
// Tracing using Ray Sampling", HPG 2013, Algorithm 1); section numbers refer to that paper.
// One recursion per batch. Large nodes run their partitions, binning and leaves in parallel,
// and with SecondChild::split a node's second child starts beside its first as a task; every
// parallel step is deterministic, so the recursion is the same for any thread count.
// Statistics are hooked in through the Observer (edacrt_observer.h); NullObserver compiles
// them out.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <utility>
#include <vector>

#include "geometry/aabb.h"
#include "geometry/binning.h"
#include "geometry/ray.h"
#include "geometry/triangle.h"
#include "trace/edacrt_params.h"
#include "trace/leaf_kernels.h"
#include "trace/ray_filter.h"
#include "trace/ray_sampling.h"
#include "trace/ray_stream.h"
#include "trace/stable_partition.h"
#include "trace/trace_stats.h"
#include "trace/tracer.h"
#include "util/frame_memory.h"
#include "util/hash_random.h"

namespace edacrt {

/// Per-frame triangle data: one entry per triangle in scene order, or per piece of a pre-split
/// triangle (a piece intersects as its whole scene triangle, triangles[prims[i]]).
struct EdacrtScene {
    const Triangle* triangles = nullptr;  // the scene's
    FrameVector<Aabb> bounds;
    FrameVector<glm::vec3> centroids;
    FrameVector<std::uint32_t> prims;  // the scene triangle of each (the pieces of pre-split ones)
    Aabb box;
};

/// A subproblem: the rays that reach V, and the triangles whose bounds make up V.
struct Node {
    Aabb box;               // V
    std::size_t ray_begin;  // the node's rays are stream positions [ray_begin, + ray_count)
    std::size_t ray_count;
    std::uint32_t* tris;
    std::size_t tri_count;
    int depth;
    std::uint64_t path;  // bit d set: this node's ancestor at depth d + 1 was visited second
};

/// The split chosen for a node.
struct Split {
    BinAxis bins;       // the axis and the K bins of the centroids along it
    int last_left_bin;  // bins 0..last_left_bin go left
    Aabb box[2];        // left, right
    std::size_t count[2];
    float alpha[2];  // estimated hit ratios
    int first;       // the side visited first
    AlphaSource alpha_source;
    std::uint32_t samples;  // rays sampled for alpha or the order
};

/// The phases of a node's work, timed apart by statistics runs.
enum class Phase { sampling, binning, filtering, leaves };

/// Observer with empty hooks: the fast path. See RecordingObserver for what each hook means.
/// kConcurrent: the hooks may be called from concurrent subtrees (the recursion otherwise runs
/// its subtrees one after the other, in the same order).
struct NullObserver {
    static constexpr bool kConcurrent = true;
    struct Visit {};
    struct Timer {};
    void root(std::uint32_t*, std::size_t, std::size_t, double) {}
    Visit enter(const Node&) { return {}; }
    Timer time(Phase, int) { return {}; }
    void sampled(const Node&, std::uint32_t, std::uint64_t) {}
    void sampled_ray(std::uint32_t, std::uint32_t) {}
    void candidate(Visit&, const CandidateSplit&) {}
    void split(Visit&, const Node&, const Split&) {}
    void child(Visit&, const Node&, const Split&, int, int, bool, const Node&) {}
    void leaf_ray(std::uint32_t, std::uint32_t) {}
    void hit(std::uint32_t, const Node&) {}
    void leaf(Visit&, const Node&, std::uint64_t) {}
    void speculated(const Node&) {}
    struct HitState {};
    HitState hit_state(std::uint32_t) const { return {}; }
    void restore_hit(std::uint32_t, const HitState&) {}
};

/// Paths record the first 64 levels; order statistics cover those.
inline constexpr int kPathLevels = 64;

/// The recursion's depth is bounded, so no input can overflow the stack. A split that peels a
/// few triangles off a node whose rays enter both children alike (a fan of thin triangles
/// sharing a corner: every alpha is 1, every candidate costs the same) can repeat once per
/// triangle; from kBalancedDepth on, nodes take their most balanced candidate, which halves
/// them in the usual case, and a node at kMaxDepth is a leaf whatever its size. Real scenes
/// stay far above both: 30-32 levels for 1M camera rays in Sponza and Conference.
inline constexpr int kBalancedDepth = 96;
inline constexpr int kMaxDepth = 160;

/// A thread's scratch for the nodes it works on, sized once and reused by every node. A node
/// uses it only between its nested parallel calls, which run isolated, so no other node's work
/// can interleave on the thread meanwhile.
struct RecursionScratch {
    PartitionScratch partition;  // of the triangles
    // The bin of the node's i-th triangle, from the split's binning (K <= 256), so that the
    // partition reads it in order instead of each triangle's centroid again. An enum, not a
    // char type: a char store may alias anything and would reload every operand per triangle.
    enum class BinIndex : std::uint8_t {};
    std::vector<BinIndex> bin_of;
    std::vector<Bin> bins;
    std::vector<BinSplit> splits;
    SampleCounts sampling;
    LeafScratch leaf;

    void reserve(int k, std::size_t triangles) {
        const auto K = std::size_t(k);
        partition.reserve(triangles);
        bin_of.resize(std::max(bin_of.size(), triangles));
        if (bins.size() == K) return;
        bins.resize(K);
        splits.resize(K - 1);
        sampling.resize(k);
    }
};
using RecursionScratches = tbb::enumerable_thread_specific<RecursionScratch>;

/// The threads this recursion's tasks may run on: the arena's, as --threads limits them.
inline int worker_threads() {
    return std::min(
        tbb::this_task_arena::max_concurrency(),
        int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
}

template <Query Q, class Observer>
class Recursion {
  public:
    Recursion(const EdacrtParams& params, const EdacrtScene& scene, const RayBatch& batch,
              RecursionScratches& scratch, Observer& observer)
        : p_(params),
          scene_(scene),
          batch_(batch),
          scratches_(scratch),
          obs_(observer),
          split_second_(params.second_child == SecondChild::split && worker_threads() > 1) {}

    /// The ray-box and ray-triangle tests done so far.
    TraceStats totals() const { return {0, box_tests_, triangle_tests_}; }

    /// Moves the rays that reach `box` before their current hit to the front; returns how many.
    std::size_t filter(std::size_t begin, std::size_t count, const Aabb& box) {
        box_tests_ += count;
        return isolated([&] { return filter_rays(batch_.stream, begin, count, box); });
    }

    /// Algorithm 1.
    void run(const Node& node) {
        if (node.ray_count == 0) return;
        typename Observer::Visit visit = obs_.enter(node);
        Split split;
        if (node.ray_count <= p_.leaf_rays || triangle_leaf(p_, node.tri_count, node.ray_count) ||
            node.depth >= kMaxDepth || !choose_split(node, split, visit)) {
            leaf(node, visit);
            return;
        }
        obs_.split(visit, node, split);
        std::uint32_t* middle;
        {
            // Each triangle's bin, as binning left it (RecursionScratch::bin_of).
            RecursionScratch& sc = scratch();
            [[maybe_unused]] auto timer = obs_.time(Phase::binning, node.depth);
            middle =
                node.tris + isolated([&] {
                    return partition(node.tris, node.tri_count, sc.partition, [&](std::size_t i) {
                        return int(sc.bin_of[i]) <= split.last_left_bin;
                    });
                });
        }
        assert(std::size_t(middle - node.tris) == split.count[0]);
        std::uint32_t* child_tris[2] = {node.tris, middle};
        const auto child = [&](int side, int visit_index, std::size_t begin, std::size_t count) {
            Node c{split.box[side],   begin,          count,    child_tris[side],
                   split.count[side], node.depth + 1, node.path};
            if (visit_index == 1 && node.depth < kPathLevels)
                c.path |= std::uint64_t(1) << node.depth;
            return c;
        };
        // Near child first (Section 3.3): its hits shorten t_far, which culls rays from the
        // second child's filter. Filtering is skipped where it costs more than it saves
        // (Section 3.4).
        const int first_side = split.first, second_side = 1 - split.first;
        const bool first_skipped =
            skip_filter(node, split, first_side) && !forgoes_task(node, split);
        const bool second_skipped = skip_filter(node, split, second_side);
        Node first = child(first_side, 0, node.ray_begin, node.ray_count);
        if (!first_skipped) first.ray_count = timed_filter(node, first.box, node.ray_count);
        obs_.child(visit, node, split, first_side, 0, first_skipped, first);
        // The second child's rays, from the node's rays in [begin, begin + count).
        const auto second = [&](std::size_t begin, std::size_t count) {
            const Node part{node.box,       begin,      count,    node.tris,
                            node.tri_count, node.depth, node.path};
            Node c = child(second_side, 1, begin, count);
            if (!second_skipped) c.ray_count = timed_filter(part, c.box, count);
            obs_.child(visit, part, split, second_side, 1, second_skipped, c);
            return c;
        };
        // SecondChild::split: the rays that missed the first child's box (after its rays in
        // the stream) cannot be culled by its hits, so they go to the second child at once, as
        // a task beside the first child (disjoint rays, triangles and stream ranges); those
        // that reached it go once its hits have culled them. The second child then recurses
        // twice (its binning, sampling and partition again, and a few missed rays make a
        // brute-force leaf over all its triangles), so only a missed part large enough for a
        // task of its own is split off, and only where a task can run beside the first child
        // (split_second_): a smaller part waits for the first child, as in the paper.
        // Speculation (speculates()): a node of few rays and many triangles runs its second
        // child beside the first on a copy of its rays; a statistics run, in turn, as if beside.
        if (speculates(node, split)) {
            obs_.speculated(node);
            if constexpr (Observer::kConcurrent)
                run_beside(first, child(second_side, 1, 0, node.ray_count), second_skipped);
            else
                run_as_if_beside(first, node.ray_count,
                                 [&] { return second(node.ray_begin, node.ray_count); });
            return;
        }
        const std::size_t missed = node.ray_count - first.ray_count;
        if (!split_second_ || missed < kTaskRays) {
            run(first);
            run(second(node.ray_begin, node.ray_count));
            return;
        }
        const std::size_t missed_begin = node.ray_begin + first.ray_count;
        if constexpr (!Observer::kConcurrent) {
            run(first);
            run(second(missed_begin, missed));
        } else {
            const Node early = second(missed_begin, missed);
            tbb::task_group beside;
            beside.run([&] { run(early); });
            run(first);
            beside.wait();
        }
        run(second(node.ray_begin, first.ray_count));
    }

    /// The smallest missed part split off as a task beside the first child.
    static constexpr std::size_t kTaskRays = 512;
    /// The levels where the first child is filtered for the second child's task whatever its
    /// alpha: the root and its children (measured on 2 threads against 0-1, 0-2, 0-3, 0-7 and
    /// every level). One count for any number of threads keeps the recursion the same on all.
    static constexpr int kTaskLevels = 2;
    /// ...and only for a task of at least this share of the node's rays: a smaller one gains
    /// less than the second recursion costs (the teapot's shadow rays on 2 threads: 51 box
    /// tests per ray with the share, as before the rule, and 53 without it).
    static constexpr float kTaskShare = 0.2f;

    /// Speculation, for closest-hit nodes of few rays and many triangles: too few rays for
    /// SecondChild::split's task to pay for the second child's second recursion (binning and
    /// partitions are work per triangle, whatever the rays), so a thread would idle. The second
    /// child runs beside the first instead, on a copy of the node's rays, no hit of the first
    /// child culling them; each ray then keeps the hit the paper's order would have kept. Any-hit
    /// rays stay in the paper's order: one hit in the first child ends a ray, and without that
    /// the second child did more work than the task saved (the bunny's shadow rays: 5%).
    static constexpr std::size_t kSpeculateRays = 32768;      // the copy's bound: 1.8 MB
    static constexpr std::size_t kSpeculateTriangles = 4096;  // in each child

  private:
    bool speculates(const Node& node, const Split& split) const {
        return Q == Query::closest && split_second_ && node.ray_count <= kSpeculateRays &&
               std::min(split.count[0], split.count[1]) >= kSpeculateTriangles;
    }

    /// The first child on this batch and `second` (its rays: all the node's, from position 0)
    /// on a copy of the node's rays with hits of its own, side by side. The copy starts with each
    /// ray's current hit, so the leaves' skip of the current triangle (kSkipsCurrentHit) holds.
    void run_beside(const Node& first, Node second, bool second_skipped) {
        const std::size_t begin = first.ray_begin, n = second.ray_count;
        RayStreamStorage storage;
        const RayStream rays = storage.fill(batch_.stream, begin, n);
        // The copy's rays are numbered from 0, its hits in that order.
        const std::vector<std::uint32_t> ids(rays.id, rays.id + n);
        std::iota(rays.id, rays.id + n, std::uint32_t(0));
        std::vector<Hit> hits(n);
        for (std::size_t i = 0; i < n; ++i) hits[i] = batch_.hits[ids[i]];
        const RayBatch copy{rays, hits.data()};  // outlives `beside`, which keeps a reference
        Recursion beside(p_, scene_, copy, scratches_, obs_);
        if (!second_skipped) second.ray_count = beside.filter(0, n, second.box);
        tbb::task_group task;
        task.run([&] { beside.run(second); });
        run(first);
        task.wait();
        keep_nearer(first.ray_begin, n, ids, hits);
        const TraceStats tests = beside.totals();
        box_tests_ += tests.ray_box_tests;
        triangle_tests_ += tests.ray_triangle_tests;
    }

    /// What run_beside does, one child after the other on this batch, so that statistics see
    /// the rays by their numbers and stream positions: the second child (`second()`, which
    /// filters the node's `count` rays) gets them as the first child found them, and the
    /// node's part of the stream is left as the first child leaves it.
    template <class SecondChild>
    void run_as_if_beside(const Node& first, std::size_t count, const SecondChild& second) {
        const std::size_t begin = first.ray_begin;
        const RayStream& s = batch_.stream;
        RayStreamStorage before_storage, after_storage;
        const RayStream before = before_storage.fill(s, begin, count);
        const std::span<const std::uint32_t> ids(before.id, count);
        std::vector<Hit> start(count), first_hits(count), second_hits(count);
        for (std::size_t i = 0; i < count; ++i) start[i] = batch_.hits[ids[i]];
        run(first);
        // The statistics' record of each ray's hit, as the first child leaves it.
        std::vector<typename Observer::HitState> first_state(count);
        for (std::size_t i = 0; i < count; ++i) first_state[i] = obs_.hit_state(ids[i]);
        const RayStream after = after_storage.fill(s, begin, count);
        for (std::size_t i = 0; i < count; ++i) {
            first_hits[i] = std::exchange(batch_.hits[ids[i]], start[i]);
        }
        copy_rays(before, 0, s, begin, count);
        run(second());
        for (std::size_t i = 0; i < count; ++i)
            second_hits[i] = std::exchange(batch_.hits[ids[i]], first_hits[i]);
        copy_rays(after, 0, s, begin, count);
        keep_nearer(begin, count, ids, second_hits);
        for (std::size_t i = 0; i < count; ++i)
            if (!nearer(second_hits[i], first_hits[i])) obs_.restore_hit(ids[i], first_state[i]);
    }

    /// Whether the second child's hit replaces the first child's (keep_nearer).
    static bool nearer(const Hit& second, const Hit& first) {
        return second.hit() && second.t <= first.t;
    }

    /// Each of the node's rays (stream positions [begin, + count), numbered `ids` in the order
    /// of `second_hits`) keeps the hit the paper's order would: there the second child meets a
    /// ray with the first child's hit as its t_far and takes a hit at t <= t_far, so the second
    /// child's hit wins when it is at most as far. The rays then carry their hits' distances
    /// on (t_far), as after the paper's order.
    void keep_nearer(std::size_t begin, std::size_t count, std::span<const std::uint32_t> ids,
                     std::span<const Hit> second_hits) {
        for (std::size_t i = 0; i < ids.size(); ++i) {
            Hit& hit = batch_.hits[ids[i]];
            if (nearer(second_hits[i], hit)) hit = second_hits[i];
        }
        const RayStream& s = batch_.stream;
        for (std::size_t i = begin; i < begin + count; ++i)
            if (const Hit& hit = batch_.hits[s.id[i]]; hit.hit())
                s.t_far[i] = std::min(s.t_far[i], hit.t);
    }

    /// The calling thread's scratch, sized for this recursion.
    RecursionScratch& scratch() {
        RecursionScratch& s = scratches_.local();
        s.reserve(p_.bins, scene_.prims.size());
        return s;
    }

    /// Runs a nested parallel call so that the waiting thread takes no unrelated task (another
    /// subtree, which would reuse its scratch).
    template <class F>
    static auto isolated(const F& f) {
        return tbb::this_task_arena::isolate(f);
    }

    /// The node's rays [ray_begin, + count) filtered by `box`, timed.
    std::size_t timed_filter(const Node& node, const Aabb& box, std::size_t count) {
        [[maybe_unused]] auto timer = obs_.time(Phase::filtering, node.depth);
        return filter(node.ray_begin, count, box);
    }

    /// SecondChild::split takes the second child's task from the rays the first child's
    /// filter rejects, so skipping that filter (Section 3.4 prices it by box tests alone)
    /// forgoes the task. Near the root, where a thread would otherwise idle, a large task is
    /// worth more (the bunny's shadow rays: 10% of the frame on 2 threads); deeper, or small,
    /// its second recursion costs more than it gains.
    bool forgoes_task(const Node& node, const Split& split) const {
        const float missed = 1.0f - split.alpha[split.first];
        return split_second_ && node.depth < kTaskLevels && missed >= kTaskShare &&
               missed * float(node.ray_count) >= float(kTaskRays);
    }

    bool skip_filter(const Node& node, const Split& split, int side) const {
        return split.alpha[side] >
               filter_skip_threshold(p_, std::uint32_t(split.count[side]), node.ray_count);
    }

    /// Binning (Section 3.1, after Wald 2007), the hit ratios (Section 3.2), the cost model and
    /// the traversal order (Section 3.3). False when no split separates the triangles or, in
    /// nodes of at most cost_leaf_max_tris triangles, none is cheaper than a leaf.
    bool choose_split(const Node& node, Split& split, typename Observer::Visit& visit) {
        RecursionScratch& sc = scratch();
        {
            [[maybe_unused]] auto timer = obs_.time(Phase::binning, node.depth);
            if (!bin(node, split, sc)) return false;
        }
        const NodeSampling sampling = estimate_hit_ratios(node, split.bins.axis, sc);
        const std::uint32_t samples = sampling.count;
        const bool sampled = samples > 0;
        const bool sampled_alpha = sampled && p_.hit_ratio == HitRatio::sampled;
        split.samples = samples;
        split.alpha_source = !sampled_alpha       ? AlphaSource::area
                             : sampling.every_ray ? AlphaSource::every_ray
                                                  : AlphaSource::sampled;
        const float box_area = node.box.surface_area();
        // C(V -> {V_L, V_R}) = C_T + C_I (alpha_L N_L + alpha_R N_R), per ray of the node;
        // a leaf costs C_I N. Every candidate pays the same C_T and C_I per test, so the
        // cheapest is the one of fewest expected tests, compared as such so that C_T and C_I
        // decide only against the leaf (param_no_effect_reason() relies on it).
        float best_key = kInfinity, best_cost = kInfinity;
        // Deep nodes: the most balanced candidate instead of the cheapest (kBalancedDepth).
        const bool balance = node.depth >= kBalancedDepth;
        // The side each candidate visits first (Section 3.3): the child most sampled rays
        // enter first, or the near one by the majority sign of the rays' direction on the axis.
        const bool by_samples = sampled && p_.order == TraversalOrder::sampled;
        // The sign count is a pass over the node's rays: made once, and only if asked for.
        int sign_first = -1;
        const auto first_side = [&](int j) {
            if (by_samples) return sc.sampling.left_first[j] >= sc.sampling.right_first[j] ? 0 : 1;
            if (sign_first < 0)
                sign_first = p_.order == TraversalOrder::left_first ||
                                     2 * count_negative(node, split.bins.axis) <= node.ray_count
                                 ? 0
                                 : 1;
            return sign_first;
        };
        const bool unstopped = sampled_alpha && p_.far_child == FarChild::unstopped;
        int best = -1;
        for (int j = 0; j < p_.bins - 1; ++j) {
            const BinSplit& s = sc.splits[j];
            CandidateSplit c{s.left, s.right, std::uint32_t(s.left_count),
                             std::uint32_t(s.right_count)};
            c.plane = split.bins.origin + float(j + 1) / split.bins.scale;
            if (c.left_triangles == 0 || c.right_triangles == 0) {
                c.cost = kInfinity;
                obs_.candidate(visit, c);
                continue;
            }
            if (sampled_alpha) {
                c.alpha_left = float(sc.sampling.left_hits[j]) / float(samples);
                c.alpha_right = float(sc.sampling.right_hits[j]) / float(samples);
            } else {  // the surface-area heuristic's conditional probabilities
                c.alpha_left = box_area > 0.0f ? c.left.surface_area() / box_area : 1.0f;
                c.alpha_right = box_area > 0.0f ? c.right.surface_area() / box_area : 1.0f;
            }
            // FarChild::unstopped: a sampled ray that enters the first child's box before the
            // second's meets the first child's triangles first; taken as stopped there (its hit
            // culls it from the second child's filter), it drops out of the second child's
            // term. What remains is the share of samples that enter the second box first
            // (sample_rays' *_first counts), so C = C_T + C_I (alpha_f N_f + phi_s N_s),
            // phi_s <= alpha_s. Rays that start inside both boxes count for the side they head
            // to: the nearer parts of each child are visited first further down.
            float weight[2] = {c.alpha_left, c.alpha_right};
            if (unstopped) {
                const int second = 1 - first_side(j);
                const std::uint32_t entered_first =
                    second == 0 ? sc.sampling.left_first[j] : sc.sampling.right_first[j];
                weight[second] = float(entered_first) / float(samples);
            }
            const float tests =
                weight[0] * float(c.left_triangles) + weight[1] * float(c.right_triangles);
            c.cost = p_.cost_traversal + p_.cost_intersect * tests;
            obs_.candidate(visit, c);
            const float key =
                balance ? std::abs(float(c.left_triangles) - float(c.right_triangles)) : tests;
            if (key < best_key) {
                best_key = key;
                best_cost = c.cost;
                best = j;
                split.count[0] = c.left_triangles;
                split.count[1] = c.right_triangles;
                split.alpha[0] = c.alpha_left;
                split.alpha[1] = c.alpha_right;
            }
        }
        if (best < 0 || (!balance && cost_leaf_tested(p_, std::uint32_t(node.tri_count)) &&
                         !(best_cost < p_.cost_intersect * float(node.tri_count))))
            return false;
        split.last_left_bin = best;
        split.box[0] = sc.splits[best].left;
        split.box[1] = sc.splits[best].right;
        split.first = first_side(best);
        return true;
    }

    /// Chooses the bins' axis and range and bins the node's triangles; false when they cannot
    /// be separated (all centroids in one point).
    bool bin(const Node& node, Split& split, RecursionScratch& sc) {
        const int axis = node.box.longest_axis();
        if (p_.binning == Binning::node_box &&
            BinAxis::make(axis, node.box.lo[axis], node.box.hi[axis], p_.bins, split.bins) &&
            fill_bins(node, split.bins, sc) > 1)
            return true;
        // Across the centroids' range on V's longest axis or, if they all coincide there,
        // on the axis where they spread most.
        const Aabb centroids = centroid_bounds(node);
        const int spread =
            centroids.hi[axis] > centroids.lo[axis] ? axis : centroids.longest_axis();
        if (!BinAxis::make(spread, centroids.lo[spread], centroids.hi[spread], p_.bins, split.bins))
            return false;
        fill_bins(node, split.bins, sc);
        return true;
    }

    Aabb centroid_bounds(const Node& node) const {
        const auto extend = [&](const tbb::blocked_range<std::size_t>& range, Aabb box) {
            for (std::size_t i = range.begin(); i != range.end(); ++i)
                box.extend(scene_.centroids[node.tris[i]]);
            return box;
        };
        const tbb::blocked_range<std::size_t> all(0, node.tri_count, kParallelItems);
        if (node.tri_count < kParallelItems) return extend(all, Aabb{});
        // min and max are exact, so any grouping gives the same box
        return isolated([&] {
            return tbb::parallel_reduce(all, Aabb{}, extend, [](Aabb a, const Aabb& b) {
                a.extend(b);
                return a;
            });
        });
    }

    /// Bins the triangles and sweeps the bins (geometry/binning.h): candidate j puts bins 0..j
    /// left. Returns the number of non-empty bins.
    int fill_bins(const Node& node, const BinAxis& axis, RecursionScratch& sc) {
        isolated([&] {
            edacrt::fill_bins(
                sc.bins, 0, node.tri_count,
                [&](std::size_t i) {
                    const int bin = axis(scene_.centroids[node.tris[i]]);
                    sc.bin_of[i] = RecursionScratch::BinIndex(bin);
                    return bin;
                },
                [&](std::size_t i) -> const Aabb& { return scene_.bounds[node.tris[i]]; },
                kParallelItems);
        });
        sweep_bins(sc.bins, sc.splits);
        return int(std::count_if(sc.bins.begin(), sc.bins.end(),
                                 [](const Bin& b) { return b.count > 0; }));
    }

    /// Ray sampling (Section 3.2, ray_sampling.h): for every candidate, how many sampled rays
    /// hit each child box, and which child each enters first. Returns the sampling, count 0
    /// when this node takes surface-area ratios instead.
    NodeSampling estimate_hit_ratios(const Node& node, int axis, RecursionScratch& sc) {
        const bool wanted =
            p_.hit_ratio == HitRatio::sampled || p_.order == TraversalOrder::sampled;
        const NodeSampling sampling = wanted ? node_sampling(p_, node.ray_count) : NodeSampling{};
        if (sampling.count == 0) return sampling;
        [[maybe_unused]] auto timer = obs_.time(Phase::sampling, node.depth);
        // Drawn rays come from a generator seeded by the node, so a batch traces the same way
        // every time.
        const auto tests_per_sample = std::uint32_t(2 * (p_.bins - 1));
        box_tests_ += std::uint64_t(sampling.count) * tests_per_sample;
        obs_.sampled(node, sampling.count, std::uint64_t(sampling.count) * tests_per_sample);
        const RaySample sample{sampling.count, !sampling.every_ray,
                               hash_combine(hash_combine(p_.seed, std::uint32_t(node.depth)),
                                            std::uint32_t(node.ray_count))};
        sample_rays(batch_.stream, node.ray_begin, node.ray_count, sample, axis,
                    std::span<const BinSplit>(sc.splits), sc.sampling,
                    [&](std::uint32_t ray) { obs_.sampled_ray(ray, tests_per_sample); });
        return sampling;
    }

    std::size_t count_negative(const Node& node, int axis) const {
        const float* dir = batch_.stream.dir[axis] + node.ray_begin;
        const auto count = [&](const tbb::blocked_range<std::size_t>& range, std::size_t n) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) n += std::signbit(dir[i]);
            return n;
        };
        const tbb::blocked_range<std::size_t> all(0, node.ray_count, kParallelItems);
        if (node.ray_count < kParallelItems) return count(all, 0);
        return isolated(
            [&] { return tbb::parallel_reduce(all, std::size_t(0), count, std::plus<>()); });
    }

    /// Brute force: every ray against every triangle of the node, in parallel over rays when
    /// the node is large (rays are independent). Eight lanes at a time, in whichever shape
    /// takes fewer eight-lane tests: each ray against blocks of eight triangles (a few rays
    /// and many triangles), or groups of eight rays against one triangle at a time (no lane
    /// left empty by a short block). An any-hit ray that is already done (passed down
    /// unfiltered) is skipped.
    void leaf(const Node& node, typename Observer::Visit& visit) {
        [[maybe_unused]] auto timer = obs_.time(Phase::leaves, node.depth);
        LeafScratch& sc = scratch().leaf;
        const LeafTriangles tris{node.tris, node.tri_count, scene_.triangles, scene_.prims.data()};
        const std::size_t groups = (node.ray_count + 7) / 8, blocks = (node.tri_count + 7) / 8;
        const bool by_groups = groups * node.tri_count <= node.ray_count * blocks;
        if (by_groups)
            sc.pack_corners(tris);
        else
            sc.pack_blocks(tris);
        const LeafHooks hooks{obs_, node};
        const std::size_t rays_end = node.ray_begin + node.ray_count;
        const auto trace = [&](const tbb::blocked_range<std::size_t>& range, std::uint64_t tests) {
            if (!by_groups)
                return tests +
                       trace_rays<Q>(batch_, range.begin(), range.end(), tris, sc.blocks, hooks);
            return tests + trace_ray_groups<Q>(batch_, node.ray_begin + 8 * range.begin(),
                                               std::min(node.ray_begin + 8 * range.end(), rays_end),
                                               tris, sc.corners, sc.prims, hooks);
        };
        // Over groups of eight rays, or over rays.
        const tbb::blocked_range<std::size_t> all =
            by_groups ? tbb::blocked_range<std::size_t>(0, groups, 2)
                      : tbb::blocked_range<std::size_t>(node.ray_begin, rays_end, 16);
        const std::uint64_t tests =
            node.ray_count * node.tri_count < kParallelLeafTests ? trace(all, 0) : isolated([&] {
                return tbb::parallel_reduce(all, std::uint64_t(0), trace, std::plus<>());
            });
        triangle_tests_ += tests;
        obs_.leaf(visit, node, tests);
    }

    /// The observer's per-ray hooks, as the leaf kernels call them.
    struct LeafHooks {
        Observer& obs;
        const Node& node;
        void hit(std::uint32_t ray) const { obs.hit(ray, node); }
        void traced(std::uint32_t ray, std::uint32_t tests) const { obs.leaf_ray(ray, tests); }
    };

    /// Leaves with at least this many ray-triangle pairs trace their rays in parallel.
    static constexpr std::size_t kParallelLeafTests = 8192;

    const EdacrtParams& p_;
    const EdacrtScene& scene_;
    const RayBatch& batch_;
    RecursionScratches& scratches_;
    Observer& obs_;
    // SecondChild::split where a task can run beside the first child: on one thread the
    // second child's rays all wait for the first child, as with after_first.
    const bool split_second_;
    std::atomic<std::uint64_t> box_tests_{0}, triangle_tests_{0};
};

}  // namespace edacrt
