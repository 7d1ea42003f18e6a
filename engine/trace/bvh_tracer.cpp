#include "trace/bvh_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>

#include "geometry/binning.h"
#include "geometry/ray_box.h"

namespace edacrt {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafSize = 4;  // below this a node is always a leaf
constexpr float kTraversalCost = 1.0f;     // relative to one ray-triangle test
constexpr int kMaxDepth = 64;              // the traversal stack is sized for this

/// Top-down binned-SAH build over index ranges, partitioning prims in place.
class Builder {
  public:
    Builder(const std::vector<Aabb>& bounds, const std::vector<glm::vec3>& centroids,
            std::vector<std::uint32_t>& prims, std::vector<BvhTracer::Node>& nodes)
        : bounds_(bounds), centroids_(centroids), prims_(prims), nodes_(nodes) {}

    void build(std::uint32_t node, std::uint32_t first, std::uint32_t count, int depth) {
        Aabb box, centroid_box;
        for (std::uint32_t i = first; i < first + count; ++i) {
            box.extend(bounds_[prims_[i]]);
            centroid_box.extend(centroids_[prims_[i]]);
        }
        nodes_[node] = {box, first, count};
        if (count <= kMaxLeafSize || depth >= kMaxDepth - 1) return;

        const int axis = centroid_box.longest_axis();
        const float lo = centroid_box.lo[axis];
        const float width = centroid_box.hi[axis] - lo;
        if (!(width > 0.0f)) return;  // all centroids in one point
        const float scale = float(kBins) * (1.0f - 1e-6f) / width;
        const auto bin_of = [&](std::uint32_t prim) {
            return bin_index((centroids_[prim][axis] - lo) * scale, kBins);
        };
        std::array<Aabb, kBins> bin_box;
        std::array<std::uint32_t, kBins> bin_count{};
        for (std::uint32_t i = first; i < first + count; ++i) {
            const int bin = bin_of(prims_[i]);
            bin_box[bin].extend(bounds_[prims_[i]]);
            ++bin_count[bin];
        }
        // SAH (the cost per ray that reaches the node): candidate j puts bins 0..j left.
        std::array<float, kBins> right_cost{};
        Aabb sweep;
        std::uint32_t sweep_count = 0;
        for (int j = kBins - 1; j > 0; --j) {
            sweep.extend(bin_box[j]);
            sweep_count += bin_count[j];
            right_cost[j - 1] = sweep.surface_area() * float(sweep_count);
        }
        const float area = box.surface_area();
        float best_cost = float(count);  // the leaf
        int best = -1;
        sweep = Aabb{};
        sweep_count = 0;
        for (int j = 0; j < kBins - 1; ++j) {
            sweep.extend(bin_box[j]);
            sweep_count += bin_count[j];
            if (sweep_count == 0 || sweep_count == count) continue;
            const float cost =
                kTraversalCost + (sweep.surface_area() * float(sweep_count) + right_cost[j]) / area;
            if (cost < best_cost) {
                best_cost = cost;
                best = j;
            }
        }
        if (best < 0) return;
        const std::uint32_t* middle =
            std::partition(prims_.data() + first, prims_.data() + first + count,
                           [&](std::uint32_t prim) { return bin_of(prim) <= best; });
        const std::uint32_t left_count = std::uint32_t(middle - (prims_.data() + first));
        const std::uint32_t children = std::uint32_t(nodes_.size());
        nodes_.resize(nodes_.size() + 2);
        nodes_[node].first = children;
        nodes_[node].count = 0;
        build(children, first, left_count, depth + 1);
        build(children + 1, first + left_count, count - left_count, depth + 1);
    }

  private:
    const std::vector<Aabb>& bounds_;
    const std::vector<glm::vec3>& centroids_;
    std::vector<std::uint32_t>& prims_;
    std::vector<BvhTracer::Node>& nodes_;
};

}  // namespace

void BvhTracer::set_scene(const Scene& scene) {
    triangles_ = gather_triangles(scene);
    std::vector<Aabb> bounds(triangles_.size());
    std::vector<glm::vec3> centroids(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
        bounds[i] = conservative_bounds(triangles_[i]);
        centroids[i] = centroid(triangles_[i]);
    }
    build_bytes_ = bounds.capacity() * sizeof(Aabb) + centroids.capacity() * sizeof(glm::vec3);
    nodes_.clear();
    prims_.clear();
    if (triangles_.empty()) return;
    prims_.resize(triangles_.size());
    for (std::size_t i = 0; i < prims_.size(); ++i) prims_[i] = std::uint32_t(i);
    nodes_.reserve(2 * triangles_.size());
    nodes_.emplace_back();
    Builder(bounds, centroids, prims_, nodes_).build(0, 0, std::uint32_t(prims_.size()), 0);
}

std::size_t BvhTracer::working_bytes() const {
    return triangles_.capacity() * sizeof(Triangle) + prims_.capacity() * sizeof(std::uint32_t) +
           nodes_.capacity() * sizeof(Node) + build_bytes_;
}

TraceStats BvhTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                  TraceDetail* detail) {
    if (nodes_.empty()) {  // no triangles
        std::fill(hits.begin(), hits.end(), Hit{});
        return {rays.size(), 0, 0};
    }
    RayStats* ray_stats = detail ? detail->rays.data() : nullptr;
    return query == Query::closest ? trace_all<Query::closest>(rays, hits, ray_stats)
                                   : trace_all<Query::any>(rays, hits, ray_stats);
}

template <Query Q>
TraceStats BvhTracer::trace_all(std::span<const Ray> rays, std::span<Hit> hits,
                                RayStats* ray_stats) const {
    const auto trace_range = [&](const tbb::blocked_range<std::size_t>& range, TraceStats stats) {
        struct Entry {
            std::uint32_t node;
            float t_entry;
        };
        std::array<Entry, kMaxDepth + 1> stack;
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Ray& ray = rays[i];
            const SlabRay sray = make_slab_ray(ray);
            const WatertightRay wray = make_watertight_ray(ray);
            Hit& hit = hits[i] = Hit{};
            float t_far = ray.tmax;
            int top = 0;
            std::uint32_t box_tests = 1, triangle_tests = 0;
            if (float t_entry; intersect_box(sray, nodes_[0].box, t_far, t_entry))
                stack[top++] = {0, t_entry};
            while (top > 0) {
                const auto [index, t_entry] = stack[--top];
                if (t_entry > t_far) continue;  // behind a hit found since it was pushed
                const Node& node = nodes_[index];
                if (node.count == 0) {  // inner: the nearer child goes on top
                    float t_left = 0.0f, t_right = 0.0f;
                    box_tests += 2;
                    const bool left = intersect_box(sray, nodes_[node.first].box, t_far, t_left);
                    const bool right =
                        intersect_box(sray, nodes_[node.first + 1].box, t_far, t_right);
                    const Entry left_entry{node.first, t_left},
                        right_entry{node.first + 1, t_right};
                    if (left && right) {
                        const bool right_nearer = t_right < t_left;
                        stack[top++] = right_nearer ? left_entry : right_entry;
                        stack[top++] = right_nearer ? right_entry : left_entry;
                    } else if (left || right) {
                        stack[top++] = left ? left_entry : right_entry;
                    }
                    continue;
                }
                TriangleHit candidate;
                for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
                    ++triangle_tests;
                    const std::uint32_t prim = prims_[k];
                    if (!intersect_triangle(wray, triangles_[prim], ray.tmin, t_far, candidate))
                        continue;
                    hit = {candidate.t, std::int32_t(prim), candidate.u, candidate.v};
                    t_far = candidate.t;
                    if constexpr (Q == Query::any) {  // done: drop the rest of the stack
                        top = 0;
                        break;
                    }
                }
            }
            stats.ray_box_tests += box_tests;
            stats.ray_triangle_tests += triangle_tests;
            if (ray_stats) ray_stats[i] = {box_tests, triangle_tests, 0, 0};
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
