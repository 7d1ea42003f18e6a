#include "trace/bvh_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <bit>

#include "geometry/ray_box8.h"
#include "trace/ray_observer.h"

namespace edacrt {
namespace {

/// The children a node holds (its lanes with a box), for the box-test counters.
int lane_count(const Bvh8Node& node) {
    const __m256 lo_x = _mm256_load_ps(node.boxes.lo[0]);
    return std::popcount(
        unsigned(_mm256_movemask_ps(_mm256_cmp_ps(lo_x, _mm256_set1_ps(kInfinity), _CMP_NEQ_OQ))));
}

}  // namespace

void BvhTracer::set_scene(const Scene& scene) {
    const FrameVector<Triangle> triangles = gather_triangles(scene);
    std::vector<BvhReference> references(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
        references[i] = {conservative_bounds(triangles[i]), std::uint32_t(i)};
    Bvh bvh = build_bvh(references, options_);
    // The builder's temporaries, alive beside the members while the tree is collapsed.
    build_bytes_ = triangles.capacity() * sizeof(Triangle) +
                   references.capacity() * sizeof(BvhReference) +
                   bvh.nodes.capacity() * sizeof(bvh.nodes[0]);
    wide_ = collapse_bvh8(bvh.nodes);
    bvh_prims_ = std::move(bvh.prims);
    leaf_triangles_.resize(bvh_prims_.size());
    for (std::size_t k = 0; k < bvh_prims_.size(); ++k)
        leaf_triangles_[k] = triangles[bvh_prims_[k]];
}

UpdateWork BvhTracer::update(const Scene& scene, SceneUpdate how) {
    if (how != SceneUpdate::refit || wide_.empty() || scene.triangle_count() != bvh_prims_.size()) {
        set_scene(scene);
        return UpdateWork::rebuilt;
    }
    refit(scene);
    return UpdateWork::refitted;
}

void BvhTracer::refit(const Scene& scene) {
    const auto used = [](const Bvh8Node& node, int lane) {
        return node.boxes.lo[0][lane] != kInfinity;  // unused lanes hold empty boxes
    };
    // Leaf lanes from their triangles' conservative bounds, as build_bvh boxed them.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, wide_.size(), 64), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            Bvh8Node& node = wide_[i];
            for (int lane = 0; lane < 8; ++lane) {
                if (!used(node, lane) || node.count[lane] == 0) continue;
                Aabb box;
                for (std::uint32_t k = node.child[lane]; k < node.child[lane] + node.count[lane];
                     ++k) {
                    leaf_triangles_[k] = scene.corners(bvh_prims_[k]);
                    box.extend(conservative_bounds(leaf_triangles_[k]));
                }
                set_lane(node.boxes, lane, box);
            }
        }
    });
    // Inner lanes from their child's lanes: collapse_bvh8 stores children after their parent,
    // so from the last node back to the root every child is done before its parent.
    for (std::size_t i = wide_.size(); i-- > 0;) {
        Bvh8Node& node = wide_[i];
        for (int lane = 0; lane < 8; ++lane) {
            if (!used(node, lane) || node.count[lane] != 0) continue;
            const Bvh8Node& child = wide_[node.child[lane]];
            Aabb box;
            for (int c = 0; c < 8 && used(child, c); ++c) box.extend(lane_box(child.boxes, c));
            set_lane(node.boxes, lane, box);
        }
    }
}

std::size_t BvhTracer::working_bytes() const {
    return wide_.capacity() * sizeof(Bvh8Node) + bvh_prims_.capacity() * sizeof(std::uint32_t) +
           leaf_triangles_.capacity() * sizeof(Triangle) + build_bytes_;
}

TraceStats BvhTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                  TraceDetail* detail) {
    if (wide_.empty()) {  // no triangles
        std::fill(hits.begin(), hits.end(), Hit{});
        return {rays.size(), 0, 0};
    }
    return with_ray_observer(detail, [&](const auto& observer) {
        return query == Query::closest ? trace_all<Query::closest>(rays, hits, observer)
                                       : trace_all<Query::any>(rays, hits, observer);
    });
}

template <Query Q, class Observer>
TraceStats BvhTracer::trace_all(std::span<const Ray> rays, std::span<Hit> hits,
                                const Observer& observer) const {
    const auto trace_range = [&](const tbb::blocked_range<std::size_t>& range, TraceStats stats) {
        struct Entry {  // a child lane: an inner node, or a leaf when count > 0
            std::uint32_t child;
            std::uint32_t count;
            float t_entry;
        };
        std::array<Entry, 7 * kBvhMaxDepth + 1> stack;  // a node pushes at most 7 siblings
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Ray& ray = rays[i];
            const SlabRay1x8 sray = make_slab_ray1x8(make_slab_ray(ray));
            const WatertightRay wray = make_watertight_ray(ray);
            Hit& hit = hits[i] = Hit{};
            float t_far = ray.tmax;
            std::uint32_t box_tests = 0, triangle_tests = 0;
            Entry current{0, 0, ray.tmin};
            int top = 0;
            for (;;) {
                if (current.count == 0) {  // inner: the nearest child next, the others stacked
                    const Bvh8Node& node = wide_[current.child];
                    __m256 t_entry;
                    int mask = intersect_boxes8(sray, node.boxes, t_far, t_entry);
                    box_tests += lane_count(node);
                    if (mask != 0) {
                        alignas(32) float t[8];
                        _mm256_store_ps(t, t_entry);
                        const auto entry = [&](int lane) {
                            return Entry{node.child[lane], node.count[lane], t[lane]};
                        };
                        const int first = std::countr_zero(unsigned(mask));
                        mask &= mask - 1;
                        if (mask == 0) {
                            current = entry(first);
                            continue;
                        }
                        // Insertion sort, farthest at the bottom: at most 8 entries.
                        const int bottom = top;
                        stack[top++] = entry(first);
                        for (; mask != 0; mask &= mask - 1) {
                            const Entry e = entry(std::countr_zero(unsigned(mask)));
                            int k = top++;
                            for (; k > bottom && stack[k - 1].t_entry < e.t_entry; --k)
                                stack[k] = stack[k - 1];
                            stack[k] = e;
                        }
                        current = stack[--top];
                        continue;
                    }
                } else {
                    TriangleHit candidate;
                    bool done = false;
                    for (std::uint32_t k = current.child; k < current.child + current.count; ++k) {
                        ++triangle_tests;
                        if (!intersect_triangle(wray, leaf_triangles_[k], ray.tmin, t_far,
                                                candidate))
                            continue;
                        hit = {candidate.t, std::int32_t(bvh_prims_[k]), candidate.u, candidate.v};
                        t_far = candidate.t;
                        if constexpr (Q == Query::any) {
                            done = true;
                            break;
                        }
                    }
                    if (done) break;
                }
                // The next stacked child that starts before the nearest hit so far.
                while (top > 0 && stack[top - 1].t_entry > t_far) --top;
                if (top == 0) break;
                current = stack[--top];
            }
            stats.ray_box_tests += box_tests;
            stats.ray_triangle_tests += triangle_tests;
            observer.traced(i, box_tests, triangle_tests);
        }
        return stats;
    };
    TraceStats stats =
        tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, rays.size(), 256), TraceStats{},
                             trace_range, [](TraceStats a, const TraceStats& b) { return a += b; });
    stats.rays = rays.size();
    return stats;
}

}  // namespace edacrt
