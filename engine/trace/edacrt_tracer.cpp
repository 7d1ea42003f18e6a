// EDACRT and DACRT batches: per-batch ray data, then one recursion (edacrt_recursion.h).
#include "trace/edacrt_tracer.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>

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
    // frame. Each triangle, or with params_.presplit its pieces (presplit.h): a piece keeps its
    // whole triangle for the intersection and is binned by its clipped box's centre.
    const FrameVector<PrimReference> refs = params_.presplit != 0.0f && !triangles_.empty()
                                                ? presplit_references(triangles_, params_.presplit)
                                                : FrameVector<PrimReference>{};
    const bool pieces = !refs.empty();  // empty: no triangle was cut
    const std::size_t n = pieces ? refs.size() : triangles_.size();
    scene_.triangles.resize(n);
    scene_.bounds.resize(n);
    scene_.centroids.resize(n);
    scene_.prims.resize(n);
    scene_.box = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 4096), Aabb{},
        [&](const tbb::blocked_range<std::size_t>& range, Aabb box) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const std::uint32_t prim = pieces ? refs[i].prim : std::uint32_t(i);
                const Triangle& tri = scene_.triangles[i] = triangles_[prim];
                scene_.bounds[i] = pieces ? refs[i].box : conservative_bounds(tri);
                scene_.centroids[i] = pieces ? refs[i].box.center() : centroid(tri);
                scene_.prims[i] = prim;
                box.extend(scene_.bounds[i]);
            }
            return box;
        },
        [](Aabb a, const Aabb& b) {
            a.extend(b);
            return a;
        });
}

std::size_t EdacrtTracer::working_bytes() const {
    const auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return bytes(triangles_) + bytes(scene_.triangles) + bytes(scene_.bounds) +
           bytes(scene_.centroids) + bytes(scene_.prims) + batch_.rays.bytes() +
           bytes(batch_.tris) + scratch_bytes();
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
    const std::size_t n = rays.size(), triangles = scene_.triangles.size();
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
