#include "trace/edacrt_observer.h"

#include <algorithm>
#include <cmath>

namespace edacrt {
namespace {

std::uint16_t clamp_depth(int depth) { return std::uint16_t(std::min(depth, 65535)); }

/// Whether the ray at stream position i reaches `box` now.
bool hits_box(const RayStream& stream, std::size_t i, const Aabb& box) {
    float entry;
    return intersect_box(stream.slab_ray(i), box, stream.t_far[i], entry);
}

/// The ids of a node's rays.
std::span<const std::uint32_t> ids(const RayStream& stream, const Node& node) {
    return {stream.id + node.ray_begin, node.ray_count};
}

bool holds(const RayStream& stream, const Node& node, std::int64_t ray) {
    const auto rays = ids(stream, node);
    return ray >= 0 && std::find(rays.begin(), rays.end(), std::uint32_t(ray)) != rays.end();
}

}  // namespace

RecordingObserver::RecordingObserver(TraceDetail& detail, const RayBatch& batch,
                                     std::size_t ray_count, float cost_intersect)
    : detail_(detail),
      batch_(batch),
      cost_intersect_(cost_intersect),
      hit_path_(ray_count, 0),
      both_(ray_count, 0),
      both_at_hit_(ray_count, 0),
      second_(ray_count, 0),
      hit_depth_(ray_count, 0) {
    if (detail.max_nodes > 0) detail_.hit_node.assign(ray_count, -1);
}

RecordingObserver::Timer::~Timer() {
    observer_.level(depth_).phase_seconds[int(phase_)] +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

LevelStats& RecordingObserver::level(int depth) {
    if (detail_.levels.size() <= std::size_t(depth)) detail_.levels.resize(std::size_t(depth) + 1);
    return detail_.levels[std::size_t(depth)];
}

bool RecordingObserver::follows(const Node& node) const {
    return holds(batch_.stream, node, detail_.follow_ray);
}

void RecordingObserver::root(std::uint32_t* ids, std::size_t rays, std::size_t entered,
                             double seconds) {
    detail_.root.rays += rays;
    detail_.root.entered += entered;
    detail_.root.box_tests += rays;
    detail_.root.seconds += seconds;
    for (std::size_t i = 0; i < rays; ++i) ++detail_.rays[ids[i]].ray_box_tests;
}

RecordingObserver::Visit RecordingObserver::enter(const Node& node) {
    Visit visit;
    visit.depth = node.depth;
    if (detail_.nodes.size() < detail_.max_nodes) {
        visit.node = std::int32_t(detail_.nodes.size());
        NodeRecord& record = detail_.nodes.emplace_back();
        record.parent = next_parent_;
        if (next_parent_ >= 0) {
            NodeRecord& parent = detail_.nodes[std::size_t(next_parent_)];
            std::int32_t& slot = parent.children[next_side_];
            if (slot >= 0) parent.second_early = slot;  // the split second child's first part
            slot = visit.node;
        }
        record.depth = clamp_depth(node.depth);
        record.box = node.box;
        record.rays = std::uint32_t(node.ray_count);
        record.triangles = std::uint32_t(node.tri_count);
        record.leaf_cost = cost_intersect_ * float(node.tri_count);
        if (detail_.node_ray_ids.size() + node.ray_count <= detail_.max_node_ray_ids) {
            record.ray_ids = std::int64_t(detail_.node_ray_ids.size());
            const auto rays = ids(batch_.stream, node);
            detail_.node_ray_ids.insert(detail_.node_ray_ids.end(), rays.begin(), rays.end());
        }
    }
    entered_record_ = visit.node;
    if (follows(node)) {
        visit.followed = std::int64_t(detail_.follow.size());
        detail_.follow.push_back({visit.node, clamp_depth(node.depth)});
        visit.before = batch_.hits[detail_.follow_ray];
    }
    LevelStats& stats = level(node.depth);
    ++stats.nodes;
    stats.rays_in += node.ray_count;
    stats.triangles += node.tri_count;
    for (const std::uint32_t r : ids(batch_.stream, node)) {
        std::uint16_t& deepest = detail_.rays[r].deepest_level;
        deepest = std::max(deepest, clamp_depth(node.depth));
    }
    return visit;
}

void RecordingObserver::sampled(const Node& node, std::uint32_t samples, std::uint64_t tests) {
    LevelStats& stats = level(node.depth);
    ++stats.sampled_nodes;
    stats.sampled_rays += samples;
    stats.sample_box_tests += tests;
    stats.ray_box_tests += tests;
}

void RecordingObserver::candidate(Visit& visit, const CandidateSplit& candidate) {
    ++level(visit.depth).candidate_splits;
    if (visit.node >= 0) detail_.nodes[std::size_t(visit.node)].candidates.push_back(candidate);
}

void RecordingObserver::split(Visit& visit, const Node& node, const Split& split) {
    // Statistics only: these box tests are not counted anywhere.
    std::size_t hits[2] = {0, 0};
    const std::uint64_t bit = node.depth < kPathLevels ? std::uint64_t(1) << node.depth : 0;
    for (std::size_t i = node.ray_begin; i < node.ray_begin + node.ray_count; ++i) {
        const std::uint32_t r = batch_.stream.id[i];
        const bool left = hits_box(batch_.stream, i, split.box[0]);
        const bool right = hits_box(batch_.stream, i, split.box[1]);
        hits[0] += left;
        hits[1] += right;
        both_[r] = left && right ? both_[r] | bit : both_[r] & ~bit;
        second_[r] = (split.first == 0 ? right : left) ? second_[r] | bit : second_[r] & ~bit;
    }
    LevelStats& stats = level(node.depth);
    float alpha_true[2];
    for (int side = 0; side < 2; ++side) {
        alpha_true[side] = float(double(hits[side]) / double(node.ray_count));
        ++stats.alpha_children;
        stats.alpha_estimated_sum += split.alpha[side];
        stats.alpha_true_sum += alpha_true[side];
        const double error = std::abs(double(split.alpha[side]) - alpha_true[side]);
        stats.alpha_error_sum += error;
        stats.add_alpha_error(error);
    }
    ++stats.alpha_sources[int(split.alpha_source)];
    if (visit.node >= 0) {
        NodeRecord& record = detail_.nodes[std::size_t(visit.node)];
        record.leaf = false;
        record.axis = split.bins.axis;
        record.chosen = split.last_left_bin;
        record.left_first = split.first == 0;
        record.alpha_true[0] = alpha_true[0];
        record.alpha_true[1] = alpha_true[1];
        record.alpha_source = split.alpha_source;
        record.samples = split.samples;
    }
    if (visit.followed >= 0)
        detail_.follow[std::size_t(visit.followed)].first_side_right = split.first == 1;
}

void RecordingObserver::child(Visit& visit, const Node& node, const Split&, int side,
                              int visit_index, bool skipped, const Node& child) {
    LevelStats& stats = level(node.depth);
    stats.rays_passed += child.ray_count;
    if (++visit.children == 3) ++stats.second_splits;
    if (skipped) {
        ++stats.filters_skipped;
    } else {
        ++stats.filters_done;
        stats.filter_box_tests += node.ray_count;
        stats.ray_box_tests += node.ray_count;
        const auto rays = ids(batch_.stream, node);
        for (const std::uint32_t r : rays) ++detail_.rays[r].ray_box_tests;
        // Rejected rays that reached the box when the node was entered: the first child's
        // hits (bit d of second_ is this node's; deeper nodes set only deeper bits) culled them.
        const std::uint64_t bit = node.depth < kPathLevels ? std::uint64_t(1) << node.depth : 0;
        if (visit_index == 1)
            for (std::size_t i = child.ray_count; i < node.ray_count; ++i)
                stats.culled_by_distance += (second_[rays[i]] & bit) != 0;
    }
    if (visit.node >= 0) {
        NodeRecord& record = detail_.nodes[std::size_t(visit.node)];
        record.filter_skipped[side] = skipped;
        record.rays_passed[side] += std::uint32_t(child.ray_count);  // a split second child
                                                                     // gets two parts
    }
    // The recursion enters the child (if it has rays) right after this hook.
    next_parent_ = visit.node;
    next_side_ = side;
    if (visit.followed >= 0)
        detail_.follow[std::size_t(visit.followed)].passed[side] |=
            holds(batch_.stream, child, detail_.follow_ray);
}

void RecordingObserver::leaf(Visit& visit, const Node& node, std::uint64_t tests) {
    LevelStats& stats = level(node.depth);
    ++stats.leaves;
    stats.ray_triangle_tests += tests;
    if (visit.followed >= 0) {
        RayVisit& v = detail_.follow[std::size_t(visit.followed)];
        const Hit& now = batch_.hits[detail_.follow_ray];
        v.leaf = true;
        v.hit_here = now.prim != visit.before.prim || now.t != visit.before.t;
    }
}

void RecordingObserver::finish(std::span<const Hit> hits) {
    for (std::size_t r = 0; r < hits.size(); ++r) {
        if (!hits[r].hit()) continue;
        for (int d = 0; d < hit_depth_[r]; ++d) {
            if (!((both_at_hit_[r] >> d) & 1)) continue;
            const bool second = (hit_path_[r] >> d) & 1;
            ++(second ? level(d).order_misses : level(d).order_hits);
            detail_.rays[r].order_misses += second;
        }
    }
}

}  // namespace edacrt
