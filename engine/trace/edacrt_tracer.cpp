// The EDACRT recursion (Nabata, Iwasaki, Dobashi, Nishita, "Efficient Divide-And-Conquer Ray
// Tracing using Ray Sampling", HPG 2013, Algorithm 1). Section references are to that paper.
#include "trace/edacrt_tracer.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <iterator>

#include "geometry/binning.h"
#include "geometry/ray_box.h"
#include "util/hash_random.h"

namespace edacrt {
namespace {

/// Per-ray state of one batch, indexed by ray number.
struct RayState {
    const Ray* rays;
    const WatertightRay* wrays;
    const SlabRay* srays;
    float* t_far;  // the current search distance: closest hit so far; -inf once an any-hit ray
                   // is done, which removes it from every later filter and leaf
    Hit* hits;
    // Statistics only (null otherwise):
    RayStats* ray_stats;
    std::uint64_t* hit_path;   // at the ray's hit: bit d set = second-visited child at depth d
    std::uint16_t* hit_depth;  // depth of the leaf that produced the hit
};

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Paths record the first 64 levels; order statistics cover those.
constexpr int kPathLevels = 64;

/// The chosen split of one node.
struct Split {
    int axis;
    float bin_origin, bin_scale;  // bin of a centroid c: (c[axis] - origin) * scale
    int last_left_bin;            // bins 0..last_left_bin go left
    Aabb box[2];
    std::size_t count[2];
    float alpha[2];  // fraction of (sampled) rays that hit each child's box
    bool left_first;
};

/// Binning scratch, reused by every node of one recursion (sized K once).
struct BinScratch {
    std::vector<Aabb> bin_bounds, left_bounds, right_bounds;
    std::vector<std::size_t> bin_count;
    std::vector<std::uint32_t> left_hits, right_hits, left_first, right_first;

    explicit BinScratch(int bins)
        : bin_bounds(bins),
          left_bounds(bins),
          right_bounds(bins),
          bin_count(bins),
          left_hits(bins),
          right_hits(bins),
          left_first(bins),
          right_first(bins) {}
};

/// The recursion over one sub-batch. With kStats it also fills per-level statistics (in
/// `levels`) and per-ray ones (through RayState); without, that code is compiled out.
template <Query Q, bool kStats>
class Recursion {
  public:
    Recursion(const EdacrtParams& params, const EdacrtTracer::SceneData& scene,
              const RayState& state, BinScratch& scratch, TraceStats& stats,
              std::vector<LevelStats>& levels)
        : p_(params),
          scene_(scene),
          state_(state),
          scratch_(scratch),
          stats_(stats),
          levels_(levels) {}

    /// Statistics runs may also record nodes (up to max_nodes) and the path of one ray.
    void record(std::vector<NodeRecord>* nodes, std::size_t max_nodes,
                std::vector<RayVisit>* visits, std::int64_t follow_ray) {
        nodes_ = nodes;
        max_nodes_ = max_nodes;
        visits_ = visits;
        follow_ = follow_ray;
    }

    /// Keeps (moves to the front) the rays that reach `box` before their current hit; the
    /// tests count for level `depth`.
    std::size_t filter(std::uint32_t* rays, std::size_t count, const Aabb& box, int depth) {
        stats_.ray_box_tests += count;
        if constexpr (kStats) {
            level(depth).ray_box_tests += count;
            for (std::size_t i = 0; i < count; ++i) ++state_.ray_stats[rays[i]].ray_box_tests;
        }
        std::uint32_t* kept = std::partition(rays, rays + count, [&](std::uint32_t r) {
            float entry;
            return intersect_box(state_.srays[r], box, state_.t_far[r], entry);
        });
        return std::size_t(kept - rays);
    }

    /// `path` has bit d set where, at depth d, this node is the child visited second.
    /// `parent` and `side`: the recorded parent node and which child this is (statistics).
    void run(const Aabb& box, std::uint32_t* rays, std::size_t ray_count, std::uint32_t* tris,
             std::size_t tri_count, int depth, std::uint64_t path, std::int32_t parent = -1,
             int side_in_parent = 0) {
        if (ray_count == 0) return;
        [[maybe_unused]] Clock::time_point start;
        [[maybe_unused]] std::int32_t node = -1;      // recorded node
        [[maybe_unused]] std::int64_t followed = -1;  // recorded visit of the followed ray
        if constexpr (kStats) {
            if (nodes_ && nodes_->size() < max_nodes_) {
                node = std::int32_t(nodes_->size());
                NodeRecord& record = nodes_->emplace_back();
                record.parent = parent;
                record.depth = std::uint16_t(std::min(depth, 65535));
                record.box = box;
                record.rays = std::uint32_t(ray_count);
                record.triangles = std::uint32_t(tri_count);
                record.leaf_cost = p_.cost_intersect * float(tri_count);
                if (parent >= 0) (*nodes_)[std::size_t(parent)].children[side_in_parent] = node;
            }
            if (follow_ >= 0 &&
                std::find(rays, rays + ray_count, std::uint32_t(follow_)) != rays + ray_count) {
                followed = std::int64_t(visits_->size());
                visits_->push_back({node, std::uint16_t(std::min(depth, 65535))});
            }
            start = Clock::now();
            LevelStats& stats = level(depth);
            ++stats.nodes;
            stats.rays_in += ray_count;
            stats.triangles += tri_count;
            for (std::size_t i = 0; i < ray_count; ++i) {
                std::uint16_t& deepest = state_.ray_stats[rays[i]].deepest_level;
                deepest = std::max(deepest, std::uint16_t(std::min(depth, 65535)));
            }
        }
        Split split;
        if (ray_count <= p_.leaf_rays || tri_count <= p_.leaf_tris ||
            !choose_split(box, rays, ray_count, tris, tri_count, depth, split, node)) {
            [[maybe_unused]] Hit before;
            if constexpr (kStats)
                if (followed >= 0) before = state_.hits[follow_];
            leaf(rays, ray_count, tris, tri_count, depth, path);
            if constexpr (kStats) {
                ++level(depth).leaves;
                level(depth).seconds += seconds_since(start);
                if (followed >= 0) {
                    RayVisit& v = (*visits_)[std::size_t(followed)];
                    v.leaf = true;
                    v.hit_here = state_.hits[follow_].prim != before.prim ||
                                 state_.hits[follow_].t != before.t;
                }
            }
            return;
        }
        if constexpr (kStats) {
            if (node >= 0) {
                NodeRecord& record = (*nodes_)[std::size_t(node)];
                record.leaf = false;
                record.axis = split.axis;
                record.chosen = split.last_left_bin;
                record.left_first = split.left_first;
            }
            if (followed >= 0)
                (*visits_)[std::size_t(followed)].first_side_right = !split.left_first;
        }
        // Partition the triangles by the chosen bin boundary (Section 3.1).
        std::uint32_t* middle = std::partition(tris, tris + tri_count, [&](std::uint32_t t) {
            return bin_of(split, scene_.centroids[t]) <= split.last_left_bin;
        });
        assert(std::size_t(middle - tris) == split.count[0]);
        std::uint32_t* child_tris[2] = {tris, middle};

        // Near child first (Section 3.3), filtering unless it is not worth it (Section 3.4).
        for (const int visit : {0, 1}) {
            const int side = split.left_first == (visit == 0) ? 0 : 1;
            const std::size_t n = split.count[side];
            const bool skip_filter =
                p_.filter_skip &&
                split.alpha[side] > 1.0f - p_.cost_filter / (float(n) * p_.cost_child);
            const std::size_t passed =
                skip_filter ? ray_count : filter(rays, ray_count, split.box[side], depth);
            const std::uint64_t child_path =
                visit == 1 && depth < kPathLevels ? path | (std::uint64_t(1) << depth) : path;
            if constexpr (kStats) {
                LevelStats& stats = level(depth);
                stats.rays_passed += passed;
                ++(skip_filter ? stats.filters_skipped : stats.filters_done);
                stats.seconds += seconds_since(start);
                if (node >= 0) {
                    NodeRecord& record = (*nodes_)[std::size_t(node)];
                    record.filter_skipped[side] = skip_filter;
                    record.rays_passed[side] = std::uint32_t(passed);
                }
                if (followed >= 0)
                    (*visits_)[std::size_t(followed)].passed[side] =
                        std::find(rays, rays + passed, std::uint32_t(follow_)) != rays + passed;
            }
            run(split.box[side], rays, passed, child_tris[side], n, depth + 1, child_path, node,
                side);
            if constexpr (kStats) start = Clock::now();
        }
        if constexpr (kStats) level(depth).seconds += seconds_since(start);
    }

  private:
    /// The statistics of level `depth` (a reference valid until the next call).
    LevelStats& level(int depth) {
        if (levels_.size() <= std::size_t(depth)) levels_.resize(std::size_t(depth) + 1);
        return levels_[std::size_t(depth)];
    }

    int bin_of(const Split& split, const glm::vec3& centroid) const {
        return bin_index((centroid[split.axis] - split.bin_origin) * split.bin_scale, p_.bins);
    }

    /// Binning (Section 3.1, after Wald 2007), ray sampling and the cost model (Section 3.2),
    /// and the traversal order (Section 3.3). Returns false when no split beats a leaf or
    /// none separates the triangles.
    bool choose_split(const Aabb& box, const std::uint32_t* rays, std::size_t ray_count,
                      const std::uint32_t* tris, std::size_t tri_count, int depth, Split& split,
                      [[maybe_unused]] std::int32_t node) {
        const int K = p_.bins;
        // Bin along the longest axis of V, over the range the centroids span on it; if they
        // all coincide there, along the axis where the centroids spread most.
        Aabb centroid_box;
        for (std::size_t i = 0; i < tri_count; ++i) centroid_box.extend(scene_.centroids[tris[i]]);
        int axis = box.longest_axis();
        if (!(centroid_box.hi[axis] > centroid_box.lo[axis])) axis = centroid_box.longest_axis();
        const float width = centroid_box.hi[axis] - centroid_box.lo[axis];
        if (!(width > 0.0f)) return false;  // all centroids in one point: nothing to split
        split.axis = axis;
        split.bin_origin = centroid_box.lo[axis];
        split.bin_scale = float(K) * (1.0f - 1e-6f) / width;

        std::fill(scratch_.bin_bounds.begin(), scratch_.bin_bounds.end(), Aabb{});
        std::fill(scratch_.bin_count.begin(), scratch_.bin_count.end(), 0);
        for (std::size_t i = 0; i < tri_count; ++i) {
            const int bin = bin_of(split, scene_.centroids[tris[i]]);
            scratch_.bin_bounds[bin].extend(scene_.bounds[tris[i]]);
            ++scratch_.bin_count[bin];
        }
        // Candidate j puts bins 0..j left, j+1..K-1 right.
        Aabb sweep;
        for (int j = 0; j < K - 1; ++j) {
            sweep.extend(scratch_.bin_bounds[j]);
            scratch_.left_bounds[j] = sweep;
        }
        sweep = Aabb{};
        for (int j = K - 2; j >= 0; --j) {
            sweep.extend(scratch_.bin_bounds[j + 1]);
            scratch_.right_bounds[j] = sweep;
        }

        const std::uint32_t sampled = estimate_hit_ratios(rays, ray_count, axis, depth);
        if constexpr (kStats) level(depth).candidate_splits += std::uint64_t(K - 1);
        const float box_area = box.surface_area();
        // A split must beat the leaf's cost per ray, except in large nodes (see
        // EdacrtParams::cost_leaf_max_tris), where the cheapest split is taken.
        float best_cost =
            tri_count <= p_.cost_leaf_max_tris ? p_.cost_intersect * float(tri_count) : kInfinity;
        int best = -1;
        std::size_t left_count = 0;
        for (int j = 0; j < K - 1; ++j) {
            left_count += scratch_.bin_count[j];
            const std::size_t right_count = tri_count - left_count;
            if (left_count == 0 || right_count == 0) {
                if constexpr (kStats)
                    if (node >= 0)
                        (*nodes_)[std::size_t(node)].candidates.push_back(
                            {scratch_.left_bounds[j], scratch_.right_bounds[j],
                             std::uint32_t(left_count), std::uint32_t(right_count), 0.0f, 0.0f,
                             kInfinity});
                continue;
            }
            float alpha_left, alpha_right;
            if (p_.sampling) {
                alpha_left = float(scratch_.left_hits[j]) / float(sampled);
                alpha_right = float(scratch_.right_hits[j]) / float(sampled);
            } else {  // DACRT: the surface-area heuristic's conditional probabilities
                alpha_left =
                    box_area > 0.0f ? scratch_.left_bounds[j].surface_area() / box_area : 1.0f;
                alpha_right =
                    box_area > 0.0f ? scratch_.right_bounds[j].surface_area() / box_area : 1.0f;
            }
            const float cost =
                p_.cost_traversal + p_.cost_intersect * (alpha_left * float(left_count) +
                                                         alpha_right * float(right_count));
            if constexpr (kStats)
                if (node >= 0)
                    (*nodes_)[std::size_t(node)].candidates.push_back(
                        {scratch_.left_bounds[j], scratch_.right_bounds[j],
                         std::uint32_t(left_count), std::uint32_t(right_count), alpha_left,
                         alpha_right, cost});
            if (cost < best_cost) {
                best_cost = cost;
                best = j;
                split.count[0] = left_count;
                split.count[1] = right_count;
                split.alpha[0] = alpha_left;
                split.alpha[1] = alpha_right;
            }
        }
        if (best < 0) return false;
        split.last_left_bin = best;
        split.box[0] = scratch_.left_bounds[best];
        split.box[1] = scratch_.right_bounds[best];
        if (p_.sampling) {
            split.left_first = scratch_.left_first[best] >= scratch_.right_first[best];
        } else {  // DACRT: near child by the majority sign of the rays' direction on the axis
            std::size_t negative = 0;
            for (std::size_t i = 0; i < ray_count; ++i)
                negative += std::signbit(state_.rays[rays[i]].dir[axis]);
            split.left_first = 2 * negative <= ray_count;
        }
        return true;
    }

    /// Ray sampling (Section 3.2): for every candidate, how many of the sampled rays hit each
    /// child box, and which child each ray enters first. A ray that starts inside both boxes
    /// enters them at the same distance; it counts for the child on the side it comes from
    /// along the split axis. Returns the number of samples.
    std::uint32_t estimate_hit_ratios(const std::uint32_t* rays, std::size_t ray_count, int axis,
                                      int depth) {
        if (!p_.sampling) return 0;
        const int candidates = p_.bins - 1;
        std::fill_n(scratch_.left_hits.begin(), candidates, 0);
        std::fill_n(scratch_.right_hits.begin(), candidates, 0);
        std::fill_n(scratch_.left_first.begin(), candidates, 0);
        std::fill_n(scratch_.right_first.begin(), candidates, 0);
        // Large nodes draw sample_count rays (with replacement) from a generator seeded by the
        // node, so a batch traces the same way every time; small nodes use every ray.
        const bool subsample = ray_count > p_.sample_threshold;
        const std::uint32_t sampled = subsample ? p_.sample_count : std::uint32_t(ray_count);
        const std::uint32_t node_seed =
            hash_combine(hash_combine(p_.seed, std::uint32_t(depth)), std::uint32_t(ray_count));
        const std::uint64_t tests_per_sample = 2 * std::uint64_t(candidates);
        stats_.ray_box_tests += sampled * tests_per_sample;
        if constexpr (kStats) {
            level(depth).sampled_rays += sampled;
            level(depth).ray_box_tests += sampled * tests_per_sample;
        }
        for (std::uint32_t s = 0; s < sampled; ++s) {
            const std::uint32_t r =
                subsample ? rays[(std::uint64_t(hash_combine(node_seed, s)) * ray_count) >> 32]
                          : rays[s];
            if constexpr (kStats) state_.ray_stats[r].ray_box_tests += tests_per_sample;
            const SlabRay& ray = state_.srays[r];
            const float t_far = state_.t_far[r];
            const bool left_on_tie = !std::signbit(ray.inv_dir[axis]);
            for (int j = 0; j < candidates; ++j) {
                float left_entry = 0.0f, right_entry = 0.0f;
                const bool left = intersect_box(ray, scratch_.left_bounds[j], t_far, left_entry);
                const bool right = intersect_box(ray, scratch_.right_bounds[j], t_far, right_entry);
                scratch_.left_hits[j] += left;
                scratch_.right_hits[j] += right;
                const bool left_nearer =
                    left_entry < right_entry || (left_entry == right_entry && left_on_tie);
                scratch_.left_first[j] += left && (!right || left_nearer);
                scratch_.right_first[j] += right && (!left || !left_nearer);
            }
        }
        return sampled;
    }

    /// Brute force: every ray against every triangle of the node. An any-hit ray that is
    /// already done (passed down unfiltered) is skipped.
    void leaf(const std::uint32_t* rays, std::size_t ray_count, const std::uint32_t* tris,
              std::size_t tri_count, [[maybe_unused]] int depth,
              [[maybe_unused]] std::uint64_t path) {
        for (std::size_t i = 0; i < ray_count; ++i) {
            const std::uint32_t r = rays[i];
            float& t_far = state_.t_far[r];
            if (Q == Query::any && t_far == -kInfinity) continue;
            const float tmin = state_.rays[r].tmin;
            const WatertightRay& wray = state_.wrays[r];
            TriangleHit hit;
            std::size_t k = 0;
            while (k < tri_count) {
                const std::uint32_t t = tris[k++];
                if (!intersect_triangle(wray, scene_.triangles[t], tmin, t_far, hit)) continue;
                state_.hits[r] = {hit.t, std::int32_t(t), hit.u, hit.v};
                if constexpr (kStats) {
                    state_.hit_path[r] = path;
                    state_.hit_depth[r] = std::uint16_t(std::min(depth, kPathLevels));
                }
                if constexpr (Q == Query::any) {
                    t_far = -kInfinity;
                    break;
                }
                t_far = hit.t;
            }
            stats_.ray_triangle_tests += k;
            if constexpr (kStats) {
                level(depth).ray_triangle_tests += k;
                state_.ray_stats[r].ray_triangle_tests += std::uint32_t(k);
            }
        }
    }

    const EdacrtParams& p_;
    const EdacrtTracer::SceneData& scene_;
    const RayState& state_;
    BinScratch& scratch_;
    TraceStats& stats_;
    std::vector<LevelStats>& levels_;
    std::vector<NodeRecord>* nodes_ = nullptr;
    std::size_t max_nodes_ = 0;
    std::vector<RayVisit>* visits_ = nullptr;
    std::int64_t follow_ = -1;
};

/// Order statistics from each ray's final hit path: at every level above the leaf that
/// produced the hit, was the hit in the child visited first?
void count_order(std::span<const Hit> hits, const std::uint64_t* hit_path,
                 const std::uint16_t* hit_depth, TraceDetail& detail) {
    for (std::size_t r = 0; r < hits.size(); ++r) {
        if (!hits[r].hit()) continue;
        const int levels = hit_depth[r];
        for (int d = 0; d < levels; ++d) {
            const bool second = (hit_path[r] >> d) & 1;
            ++(second ? detail.levels[std::size_t(d)].order_misses
                      : detail.levels[std::size_t(d)].order_hits);
            detail.rays[r].order_misses += second;
        }
    }
}

}  // namespace

EdacrtTracer::EdacrtTracer(const EdacrtParams& params, Method method) : method_(method) {
    set_params(params);
}

void EdacrtTracer::set_params(const EdacrtParams& params) {
    validate(params);
    params_ = params;
}

void EdacrtTracer::set_scene(const Scene& scene) {
    scene_.triangles = gather_triangles(scene);
    scene_.bounds.resize(scene_.triangles.size());
    scene_.centroids.resize(scene_.triangles.size());
    scene_.box = Aabb{};
    for (std::size_t i = 0; i < scene_.triangles.size(); ++i) {
        const Triangle& tri = scene_.triangles[i];
        const Aabb& bounds = scene_.bounds[i] = conservative_bounds(tri);
        scene_.centroids[i] = centroid(tri);
        scene_.box.extend(bounds);
    }
}

TraceStats EdacrtTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                     TraceDetail* detail) {
    if (query == Query::closest)
        return detail ? trace_with<Query::closest, true>(rays, hits, detail)
                      : trace_with<Query::closest, false>(rays, hits, detail);
    return detail ? trace_with<Query::any, true>(rays, hits, detail)
                  : trace_with<Query::any, false>(rays, hits, detail);
}

template <Query Q, bool kStats>
TraceStats EdacrtTracer::trace_with(std::span<const Ray> rays, std::span<Hit> hits,
                                    TraceDetail* detail) {
    const std::size_t n = rays.size();
    batch_.wrays.resize(n);
    batch_.srays.resize(n);
    batch_.t_far.resize(n);
    batch_.ids.resize(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            batch_.wrays[i] = make_watertight_ray(rays[i]);
            batch_.srays[i] = make_slab_ray(rays[i]);
            batch_.t_far[i] = rays[i].tmax;
            batch_.ids[i] = std::uint32_t(i);
            hits[i] = Hit{};
        }
    });
    std::vector<std::uint64_t> hit_path(kStats ? n : 0);
    std::vector<std::uint16_t> hit_depth(kStats ? n : 0);
    const RayState state{rays.data(),         batch_.wrays.data(),
                         batch_.srays.data(), batch_.t_far.data(),
                         hits.data(),         kStats ? detail->rays.data() : nullptr,
                         hit_path.data(),     hit_depth.data()};

    // Independent sub-batches of consecutive rays (coherent for camera rays) run in parallel,
    // each with its own triangle index array and scratch.
    struct Worker {
        std::vector<std::uint32_t> tris;
        BinScratch scratch;
        TraceStats stats;
        std::vector<LevelStats> levels;
        std::vector<NodeRecord> nodes;  // recordings (statistics runs that ask for them)
        std::vector<RayVisit> visits;
    };
    tbb::enumerable_thread_specific<Worker> workers(
        [&] { return Worker{{}, BinScratch(params_.bins), {}, {}, {}, {}}; });
    const std::size_t chunk_count = std::clamp<std::size_t>(
        n / 8192, 1, 4 * std::size_t(tbb::this_task_arena::max_concurrency()));
    tbb::parallel_for(std::size_t(0), chunk_count, [&](std::size_t chunk) {
        Worker& worker = workers.local();
        worker.tris.resize(scene_.triangles.size());
        for (std::size_t i = 0; i < worker.tris.size(); ++i) worker.tris[i] = std::uint32_t(i);
        Recursion<Q, kStats> recursion(params_, scene_, state, worker.scratch, worker.stats,
                                       worker.levels);
        if constexpr (kStats)
            recursion.record(&worker.nodes, detail->max_nodes, &worker.visits, detail->follow_ray);
        std::uint32_t* ids = batch_.ids.data() + n * chunk / chunk_count;
        const std::size_t count = n * (chunk + 1) / chunk_count - n * chunk / chunk_count;
        const std::size_t inside = recursion.filter(ids, count, scene_.box, 0);
        recursion.run(scene_.box, ids, inside, worker.tris.data(), worker.tris.size(), 0, 0);
    });

    TraceStats stats;
    stats.rays = n;
    for (const Worker& worker : workers) {
        stats.ray_box_tests += worker.stats.ray_box_tests;
        stats.ray_triangle_tests += worker.stats.ray_triangle_tests;
        if constexpr (kStats) {
            if (detail->levels.size() < worker.levels.size())
                detail->levels.resize(worker.levels.size());
            for (std::size_t d = 0; d < worker.levels.size(); ++d)
                detail->levels[d] += worker.levels[d];
        }
    }
    if constexpr (kStats) {
        count_order(hits, hit_path.data(), hit_depth.data(), *detail);
        // Each worker numbered its nodes from 0 and capped them at max_nodes on its own; a
        // worker's nodes are kept whole or not at all, so every index stays valid.
        for (Worker& worker : workers) {
            const bool keep = detail->nodes.size() + worker.nodes.size() <= detail->max_nodes;
            const auto offset = std::int32_t(detail->nodes.size());
            const auto shift = [&](std::int32_t& i) { i = i >= 0 && keep ? i + offset : -1; };
            for (NodeRecord& record : worker.nodes) {
                shift(record.parent);
                shift(record.children[0]);
                shift(record.children[1]);
            }
            if (keep)
                std::move(worker.nodes.begin(), worker.nodes.end(),
                          std::back_inserter(detail->nodes));
            for (RayVisit& visit : worker.visits) {
                shift(visit.node);
                detail->follow.push_back(visit);
            }
        }
    }
    return stats;
}

}  // namespace edacrt
