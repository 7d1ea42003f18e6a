// EDACRT and DACRT batches: per-batch ray data, then one recursion (edacrt_recursion.h).
#include "trace/edacrt_tracer.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "trace/edacrt_observer.h"
#include "trace/presplit.h"

namespace edacrt {

EdacrtTracer::EdacrtTracer(const EdacrtParams& params, Method method) : method_(method) {
    set_params(params);
}

void EdacrtTracer::set_params(const EdacrtParams& params) {
    validate(params);
    const bool pieces_change = params.presplit != params_.presplit;
    params_ = params;
    if (pieces_change) prepare_triangles();
}

void EdacrtTracer::set_scene(const Scene& scene) {
    gather_triangles(scene, triangles_);
    prepare_triangles();
}

UpdateWork EdacrtTracer::update(const Scene& scene, SceneUpdate) {
    set_scene(scene);  // no structure to keep: the recursion starts from the triangles
    return UpdateWork::none;
}

void EdacrtTracer::prepare_triangles() {
    // Per frame (update_scene() of an animation): in parallel, into the storage of the last
    // frame. Each triangle, or with params_.presplit its pieces (presplit.h): a piece is binned
    // by its clipped box's centre and intersects as its whole triangle (read through prims, not
    // copied: a copy per reference was a third of this pass's writes).
    const PresplitPlan plan = params_.presplit != 0.0f && !triangles_.empty()
                                  ? plan_presplit(triangles_, params_.presplit)
                                  : PresplitPlan{};
    const bool pieces = !plan.first.empty();  // empty: no triangle is cut
    const std::size_t n = pieces ? plan.first.back() : triangles_.size();
    scene_.triangles = triangles_.data();
    scene_.bounds.resize(n);
    scene_.centroids.resize(n);
    scene_.prims.resize(n);
    constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
    struct Sums {
        Aabb box;
        std::size_t made = 0;  // references written
    };
    const Sums sums = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, triangles_.size(), 4096), Sums{},
        [&](const tbb::blocked_range<std::size_t>& range, Sums sum) {
            for (std::size_t prim = range.begin(); prim != range.end(); ++prim) {
                const Triangle& tri = triangles_[prim];
                // A triangle that can never be hit takes no reference (has_coincident_corners).
                const bool never_hit = has_coincident_corners(tri);
                if (!pieces) {
                    scene_.prims[prim] = never_hit ? kUnused : std::uint32_t(prim);
                    if (never_hit) continue;
                    scene_.bounds[prim] = conservative_bounds(tri);
                    scene_.centroids[prim] = centroid(tri);
                    sum.box.extend(scene_.bounds[prim]);
                    ++sum.made;
                    continue;
                }
                const std::size_t first = plan.first[prim], count = plan.first[prim + 1] - first;
                const std::size_t made =
                    never_hit ? 0
                    : count == 1
                        ? (scene_.bounds[first] = conservative_bounds(tri), 1)
                        : split_triangle(tri, plan.grid,
                                         std::span<Aabb>(scene_.bounds.data() + first, count));
                for (std::size_t i = first; i < first + count; ++i) {
                    scene_.prims[i] = i < first + made ? std::uint32_t(prim) : kUnused;
                    if (i >= first + made) continue;
                    scene_.centroids[i] = scene_.bounds[i].center();
                    sum.box.extend(scene_.bounds[i]);
                }
                sum.made += made;
            }
            return sum;
        },
        [](Sums a, const Sums& b) {
            a.box.extend(b.box);
            a.made += b.made;
            return a;
        });
    scene_.box = sums.box;
    // Slots left unused: triangles never hit, pieces that could not be cut.
    if (sums.made < n) {
        std::size_t kept = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (scene_.prims[i] == kUnused) continue;
            scene_.bounds[kept] = scene_.bounds[i];
            scene_.centroids[kept] = scene_.centroids[i];
            scene_.prims[kept++] = scene_.prims[i];
        }
        scene_.bounds.resize(kept);
        scene_.centroids.resize(kept);
        scene_.prims.resize(kept);
    }
}

std::size_t EdacrtTracer::working_bytes() const {
    const auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return bytes(triangles_) + bytes(scene_.bounds) + bytes(scene_.centroids) +
           bytes(scene_.prims) + batch_.rays.bytes() + bytes(batch_.tris) + scratch_bytes();
}

std::size_t EdacrtTracer::scratch_bytes() const {
    const auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    std::size_t total = 0;
    for (const RecursionScratch& s : batch_.scratch)
        total += bytes(s.partition.items) + bytes(s.partition.keep) +
                 bytes(s.partition.block_kept) + bytes(s.bins) + bytes(s.splits) +
                 s.sampling.bytes() + s.leaf.bytes();
    return total;
}

TraceStats EdacrtTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                     TraceDetail* detail) {
    return query == Query::closest ? trace_with<Query::closest>(rays, hits, detail)
                                   : trace_with<Query::any>(rays, hits, detail);
}

template <Query Q>
TraceStats EdacrtTracer::trace_with(std::span<const Ray> rays, std::span<Hit> hits,
                                    TraceDetail* detail) {
    const std::size_t n = rays.size(), triangles = scene_.prims.size();
    batch_.tris.resize(triangles);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
        std::fill(hits.begin() + range.begin(), hits.begin() + range.end(), Hit{});
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles, 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i)
            batch_.tris[i] = std::uint32_t(i);
    });
    const RayBatch batch{batch_.rays.fill(rays), hits.data()};

    // One recursion from the scene box over the rays that reach it.
    const auto trace = [&](auto& observer) {
        Recursion<Q, std::decay_t<decltype(observer)>> recursion(params_, scene_, batch,
                                                                 batch_.scratch, observer);
        const auto start = std::chrono::steady_clock::now();
        const std::size_t entered = recursion.filter(0, n, scene_.box);
        observer.root(
            batch.stream.id, n, entered,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        recursion.run(Node{scene_.box, 0, entered, batch_.tris.data(), triangles, 0, 0});
        TraceStats stats = recursion.totals();
        stats.rays = n;
        return stats;
    };
    if (!detail) {
        NullObserver observer;
        return trace(observer);
    }
    RecordingObserver observer(*detail, batch, n, params_.cost_intersect);
    const TraceStats stats = trace(observer);
    observer.finish(hits);
    return stats;
}

}  // namespace edacrt
