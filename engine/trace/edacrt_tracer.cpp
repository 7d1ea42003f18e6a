// EDACRT and DACRT batches: per-batch ray data, then one recursion (edacrt_recursion.h).
#include "trace/edacrt_tracer.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <limits>
#include <numeric>

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
    triangles_.resize(scene.triangle_count());
    prepare_triangles(&scene);
}

UpdateWork EdacrtTracer::update(const Scene& scene, SceneUpdate) {
    set_scene(scene);  // no structure to keep: the recursion starts from the triangles
    return UpdateWork::none;
}

void EdacrtTracer::prepare_triangles(const Scene* scene) {
    // Per frame (update_scene() of an animation): in parallel, into the storage of the last
    // frame. First each triangle's reference, after room for the pieces; then, with
    // params_.presplit, the triangles the plan cuts (presplit.h) give way to their pieces, placed
    // before the triangles: the large triangles are the likeliest occluders, and a leaf tests its
    // references in this order, so an any-hit ray meets them first. A piece is binned by its
    // clipped box's centre and intersects as its whole triangle (read through prims, not
    // copied: a copy per reference was a third of this pass's writes). Gathering the scene's
    // triangles in this pass saves reading them back.
    const std::size_t count = triangles_.size();
    const bool presplit = params_.presplit != 0.0f;
    // Room for every piece a plan can make (presplit_budget()).
    const std::size_t front = presplit ? 2 * presplit_budget(count, params_.presplit) : 0;
    scene_.bounds.resize(front + count);
    scene_.centroids.resize(front + count);
    scene_.prims.resize(front + count);
    areas_.resize(presplit ? count : 0);
    scene_.triangles = triangles_.data();
    constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
    struct Sums {
        Aabb box;
        Aabb corners;  // without conservative_bounds' padding: the pre-split's grid
    };
    const auto join = [](Sums a, const Sums& b) {
        a.box.extend(b.box);
        a.corners.extend(b.corners);
        return a;
    };
    const Sums sums = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, count, 4096), Sums{},
        [&](const tbb::blocked_range<std::size_t>& range, Sums sum) {
            for (std::size_t prim = range.begin(); prim != range.end(); ++prim) {
                const Triangle tri = scene ? scene->corners(prim) : triangles_[prim];
                if (scene) triangles_[prim] = tri;
                const std::size_t slot = front + prim;
                // A triangle that can never be hit takes no reference (has_coincident_corners).
                const bool never_hit = has_coincident_corners(tri);
                scene_.prims[slot] = never_hit ? kUnused : std::uint32_t(prim);
                const Aabb corners = corners_bounds(tri);
                if (presplit) {
                    areas_[prim] = box_area(corners);
                    sum.corners.extend(corners);
                }
                if (never_hit) continue;
                const Aabb box = conservative_bounds(corners);
                scene_.bounds[slot] = box;
                // With pieces, every reference is binned by its box's centre, as a piece is.
                scene_.centroids[slot] = presplit ? box.center() : centroid(tri);
                sum.box.extend(box);
            }
            return sum;
        },
        join);
    const PresplitPlan plan =
        presplit ? plan_presplit(areas_, params_.presplit, sums.corners) : PresplitPlan{};
    // cut[k]'s pieces take [first[k], first[k + 1]), ending at `front`; the slots before them
    // stay unused.
    std::vector<std::size_t> first(plan.cut.size() + 1, front);
    for (std::size_t k = plan.cut.size(); k-- > 0;) {
        assert(first[k + 1] >= plan.pieces[k]);  // within the room
        first[k] = first[k + 1] - plan.pieces[k];
    }
    std::fill(scene_.prims.begin(), scene_.prims.begin() + std::ptrdiff_t(first[0]), kUnused);
    // Cut triangle k's pieces replace its reference. The plan shares the budget out over every
    // triangle's box, so that it does not depend on the intersection test; one never hit gets
    // no pieces.
    const auto place_pieces = [&](std::size_t k) {
        const std::uint32_t prim = plan.cut[k];
        const std::size_t begin = first[k], end = first[k + 1];
        const bool never_hit = scene_.prims[front + prim] == kUnused;
        const std::size_t made =
            never_hit ? 0
                      : split_triangle(triangles_[prim], plan.grid,
                                       std::span<Aabb>(scene_.bounds.data() + begin, end - begin));
        for (std::size_t i = begin; i < end; ++i) {
            scene_.prims[i] = i < begin + made ? prim : kUnused;
            if (i < begin + made) scene_.centroids[i] = scene_.bounds[i].center();
        }
        if (!never_hit) scene_.prims[front + prim] = kUnused;
    };
    tbb::parallel_for(std::size_t(0), plan.cut.size(), place_pieces);
    scene_.box = sums.box;  // the pieces lie in their triangles' boxes
    // The slots in use, in order, are the recursion's triangles; the others (room, triangles
    // never hit or cut, pieces that could not be cut) stay where they are, as moving the rest
    // down was a serial pass. Per block of slots a count, then each block writes its own.
    constexpr std::size_t kBlock = 16384;
    const std::uint32_t* prims = scene_.prims.data();
    const std::size_t n = scene_.prims.size(), blocks = (n + kBlock - 1) / kBlock;
    std::vector<std::size_t> offset(blocks + 1, 0);
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        offset[b + 1] =
            std::size_t(std::count_if(prims + b * kBlock, prims + std::min(n, (b + 1) * kBlock),
                                      [](std::uint32_t p) { return p != kUnused; }));
    });
    std::partial_sum(offset.begin(), offset.end(), offset.begin());
    references_.resize(offset.back());
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        std::size_t out = offset[b];
        for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i)
            if (prims[i] != kUnused) references_[out++] = std::uint32_t(i);
    });
}

std::size_t EdacrtTracer::working_bytes() const {
    const auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return bytes(triangles_) + bytes(areas_) + bytes(scene_.bounds) + bytes(scene_.centroids) +
           bytes(scene_.prims) + bytes(references_) + batch_.rays.bytes() + bytes(batch_.tris) +
           scratch_bytes();
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
    const std::size_t n = rays.size(), triangles = references_.size();
    batch_.tris.resize(triangles);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
        std::fill(hits.begin() + range.begin(), hits.begin() + range.end(), Hit{});
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles, 4096), [&](const auto& range) {
        std::copy(references_.begin() + range.begin(), references_.begin() + range.end(),
                  batch_.tris.begin() + range.begin());
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
