// The EDACRT recursion (Nabata, Iwasaki, Dobashi, Nishita, "Efficient Divide-And-Conquer Ray
// Tracing using Ray Sampling", HPG 2013, Algorithm 1). Section references are to that paper.
#include "trace/edacrt_tracer.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>

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
};

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

template <Query Q>
class Recursion {
  public:
    Recursion(const EdacrtParams& params, const EdacrtTracer::SceneData& scene,
              const RayState& state, BinScratch& scratch, TraceStats& stats)
        : p_(params), scene_(scene), state_(state), scratch_(scratch), stats_(stats) {}

    /// Keeps (moves to the front) the rays that reach `box` before their current hit.
    std::size_t filter(std::uint32_t* rays, std::size_t count, const Aabb& box) {
        stats_.ray_box_tests += count;
        std::uint32_t* kept = std::partition(rays, rays + count, [&](std::uint32_t r) {
            float entry;
            return intersect_box(state_.srays[r], box, state_.t_far[r], entry);
        });
        return std::size_t(kept - rays);
    }

    void run(const Aabb& box, std::uint32_t* rays, std::size_t ray_count, std::uint32_t* tris,
             std::size_t tri_count, int depth) {
        if (ray_count == 0) return;
        Split split;
        if (ray_count <= p_.leaf_rays || tri_count <= p_.leaf_tris ||
            !choose_split(box, rays, ray_count, tris, tri_count, depth, split)) {
            leaf(rays, ray_count, tris, tri_count);
            return;
        }
        // Partition the triangles by the chosen bin boundary (Section 3.1).
        std::uint32_t* middle = std::partition(tris, tris + tri_count, [&](std::uint32_t t) {
            return bin_of(split, scene_.centroids[t]) <= split.last_left_bin;
        });
        assert(std::size_t(middle - tris) == split.count[0]);
        std::uint32_t* child_tris[2] = {tris, middle};

        // Near child first (Section 3.3), filtering unless it is not worth it (Section 3.4).
        for (const int side : {split.left_first ? 0 : 1, split.left_first ? 1 : 0}) {
            const std::size_t n = split.count[side];
            const bool skip_filter =
                p_.filter_skip &&
                split.alpha[side] > 1.0f - p_.cost_filter / (float(n) * p_.cost_child);
            const std::size_t passed =
                skip_filter ? ray_count : filter(rays, ray_count, split.box[side]);
            run(split.box[side], rays, passed, child_tris[side], n, depth + 1);
        }
    }

  private:
    int bin_of(const Split& split, const glm::vec3& centroid) const {
        const int bin = int((centroid[split.axis] - split.bin_origin) * split.bin_scale);
        return std::clamp(bin, 0, p_.bins - 1);
    }

    /// Binning (Section 3.1, after Wald 2007), ray sampling and the cost model (Section 3.2),
    /// and the traversal order (Section 3.3). Returns false when no split beats a leaf or
    /// none separates the triangles.
    bool choose_split(const Aabb& box, const std::uint32_t* rays, std::size_t ray_count,
                      const std::uint32_t* tris, std::size_t tri_count, int depth, Split& split) {
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
            if (left_count == 0 || right_count == 0) continue;
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
        stats_.ray_box_tests += std::uint64_t(sampled) * 2 * std::uint64_t(candidates);
        for (std::uint32_t s = 0; s < sampled; ++s) {
            const std::uint32_t r =
                subsample ? rays[(std::uint64_t(hash_combine(node_seed, s)) * ray_count) >> 32]
                          : rays[s];
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
              std::size_t tri_count) {
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
                if constexpr (Q == Query::any) {
                    t_far = -kInfinity;
                    break;
                }
                t_far = hit.t;
            }
            stats_.ray_triangle_tests += k;
        }
    }

    const EdacrtParams& p_;
    const EdacrtTracer::SceneData& scene_;
    const RayState& state_;
    BinScratch& scratch_;
    TraceStats& stats_;
};

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

TraceStats EdacrtTracer::trace(std::span<const Ray> rays, std::span<Hit> hits, Query query) {
    assert(rays.size() == hits.size());
    return query == Query::closest ? trace_batch<Query::closest>(rays, hits)
                                   : trace_batch<Query::any>(rays, hits);
}

template <Query Q>
TraceStats EdacrtTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits) {
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
    const RayState state{rays.data(), batch_.wrays.data(), batch_.srays.data(), batch_.t_far.data(),
                         hits.data()};

    // Independent sub-batches of consecutive rays (coherent for camera rays) run in parallel,
    // each with its own triangle index array and scratch.
    struct Worker {
        std::vector<std::uint32_t> tris;
        BinScratch scratch;
        TraceStats stats;
    };
    tbb::enumerable_thread_specific<Worker> workers([&] {
        return Worker{{}, BinScratch(params_.bins), {}};
    });
    const std::size_t chunk_count = std::clamp<std::size_t>(
        n / 8192, 1, 4 * std::size_t(tbb::this_task_arena::max_concurrency()));
    tbb::parallel_for(std::size_t(0), chunk_count, [&](std::size_t chunk) {
        Worker& worker = workers.local();
        worker.tris.resize(scene_.triangles.size());
        for (std::size_t i = 0; i < worker.tris.size(); ++i) worker.tris[i] = std::uint32_t(i);
        Recursion<Q> recursion(params_, scene_, state, worker.scratch, worker.stats);
        std::uint32_t* ids = batch_.ids.data() + n * chunk / chunk_count;
        const std::size_t count = n * (chunk + 1) / chunk_count - n * chunk / chunk_count;
        const std::size_t inside = recursion.filter(ids, count, scene_.box);
        recursion.run(scene_.box, ids, inside, worker.tris.data(), worker.tris.size(), 0);
    });

    TraceStats stats;
    stats.rays = n;
    for (const Worker& worker : workers) {
        stats.ray_box_tests += worker.stats.ray_box_tests;
        stats.ray_triangle_tests += worker.stats.ray_triangle_tests;
    }
    return stats;
}

}  // namespace edacrt
