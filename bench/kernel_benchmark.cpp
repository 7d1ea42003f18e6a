// Google Benchmark of the divide-and-conquer kernels, each against the scalar code it replaced,
// on the rays and triangles of a closed sphere seen from outside (camera-like rays aimed at it):
//   filter     the in-place 8-wide partition of a ray stream by a box (filter_rays) against a
//              stable partition of ray ids with the scalar slab test;
//   sampling   one ray against the 2(K-1) = 14 candidate boxes of K = 8 bins, 8 at a time
//              (intersect_box8) against 14 scalar tests;
//   leaf       one ray against 16 triangles, 8 at a time (intersect_triangle8) against 16
//              scalar watertight tests;
//   binning    the triangles' centroids into K = 8 bins and the sweep (geometry/binning.h);
//   partition  the triangles' stable partition by bin (the recursion's triangle split).
//   build/edacrt_kernel_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "geometry/binning.h"
#include "geometry/ray_box8.h"
#include "geometry/triangle8.h"
#include "scene/builtin_scenes.h"
#include "trace/ray_filter.h"
#include "trace/ray_stream.h"
#include "trace/stable_partition.h"
#include "trace/tracer.h"

namespace edacrt {
namespace {

struct Data {
    FrameVector<Triangle> triangles;
    std::vector<Ray> rays;  // from a sphere of radius 3 towards random points of radius 0.8
};

const Data& data() {
    static const Data d = [] {
        Data d;
        d.triangles = gather_triangles(make_builtin_scene("builtin:sphere:subdiv=5"));
        std::mt19937 rng(1);
        std::normal_distribution<float> normal;
        const auto on_sphere = [&](float radius) {
            const glm::vec3 v(normal(rng), normal(rng), normal(rng));
            return radius * v / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        };
        for (int i = 0; i < (1 << 20); ++i) {
            const glm::vec3 org = on_sphere(3.0f);
            d.rays.push_back({org, on_sphere(0.8f) - org, 0.0f, kInfinity});
        }
        return d;
    }();
    return d;
}

// Each filter benchmark iteration filters by the next of six half boxes (the low and high half
// of each axis), so its input is the last one's output, as in the recursion: refiltering by one
// box would find its own output all in place, which the stream's filter leaves unmoved.
const Aabb kHalves[6] = {{glm::vec3(-1.0f), glm::vec3(0.0f, 1.0f, 1.0f)},
                         {glm::vec3(0.0f, -1.0f, -1.0f), glm::vec3(1.0f)},
                         {glm::vec3(-1.0f), glm::vec3(1.0f, 0.0f, 1.0f)},
                         {glm::vec3(-1.0f, 0.0f, -1.0f), glm::vec3(1.0f)},
                         {glm::vec3(-1.0f), glm::vec3(1.0f, 1.0f, 0.0f)},
                         {glm::vec3(-1.0f, -1.0f, 0.0f), glm::vec3(1.0f)}};

void filter_stream(benchmark::State& state) {
    const std::size_t n = std::size_t(state.range(0));
    const std::span<const Ray> rays(data().rays.data(), n);
    RayStreamStorage storage;
    const RayStream stream = storage.fill(rays);
    std::size_t k = 0;
    for (auto _ : state) benchmark::DoNotOptimize(filter_rays(stream, 0, n, kHalves[k++ % 6]));
    state.SetItemsProcessed(std::int64_t(n) * state.iterations());
}

void filter_scalar(benchmark::State& state) {
    const std::size_t n = std::size_t(state.range(0));
    std::vector<SlabRay> slabs;
    for (std::size_t i = 0; i < n; ++i) slabs.push_back(make_slab_ray(data().rays[i]));
    std::vector<float> t_far(n, kInfinity);
    std::vector<std::uint32_t> ids(n);
    for (std::size_t i = 0; i < n; ++i) ids[i] = std::uint32_t(i);
    PartitionScratch scratch;
    scratch.reserve(n);
    std::size_t k = 0;
    for (auto _ : state) {
        const Aabb& box = kHalves[k++ % 6];
        benchmark::DoNotOptimize(partition(ids.data(), n, scratch, [&](std::uint32_t r) {
            float entry;
            return intersect_box(slabs[r], box, t_far[r], entry);
        }));
    }
    state.SetItemsProcessed(std::int64_t(n) * state.iterations());
}

/// The 7 left and 7 right candidate boxes of 8 bins across [-1, 1] on x.
std::vector<Aabb> candidates() {
    std::vector<Aabb> boxes;
    for (int side = 0; side < 2; ++side)
        for (int j = 0; j < 7; ++j) {
            const float plane = -1.0f + 2.0f * float(j + 1) / 8.0f;
            boxes.push_back(side == 0 ? Aabb{glm::vec3(-1.0f), glm::vec3(plane, 1.0f, 1.0f)}
                                      : Aabb{glm::vec3(plane, -1.0f, -1.0f), glm::vec3(1.0f)});
        }
    return boxes;
}

void sampling8(benchmark::State& state) {
    const std::vector<Aabb> boxes = candidates();
    Boxes8 blocks[2];
    for (int side = 0; side < 2; ++side)
        blocks[side] = pack_boxes8(7, [&](int l) { return boxes[std::size_t(7 * side + l)]; });
    std::size_t i = 0;
    for (auto _ : state) {
        const SlabRay1x8 ray = make_slab_ray1x8(make_slab_ray(data().rays[i++ & 0xfffff]));
        __m256 entry[2];
        const int left = intersect_boxes8(ray, blocks[0], kInfinity, entry[0]);
        const int right = intersect_boxes8(ray, blocks[1], kInfinity, entry[1]);
        benchmark::DoNotOptimize(left);
        benchmark::DoNotOptimize(right);
        benchmark::DoNotOptimize(entry);
    }
    state.SetItemsProcessed(14 * state.iterations());
}

void sampling_scalar(benchmark::State& state) {
    const std::vector<Aabb> boxes = candidates();
    std::size_t i = 0;
    for (auto _ : state) {
        const SlabRay ray = make_slab_ray(data().rays[i++ & 0xfffff]);
        unsigned hits = 0;
        for (const Aabb& box : boxes) {
            float entry;
            hits += intersect_box(ray, box, kInfinity, entry);
            benchmark::DoNotOptimize(entry);
        }
        benchmark::DoNotOptimize(hits);
    }
    state.SetItemsProcessed(14 * state.iterations());
}

/// 16 neighbouring triangles of the sphere, and rays aimed at them.
struct Leaf {
    std::vector<Triangle> triangles;
    TriangleBlock8 blocks[2];
    TriangleCorners corners[16];
    std::vector<Ray> rays;
};

const Leaf& leaf() {
    static const Leaf l = [] {
        Leaf l;
        const auto& all = data().triangles;
        l.triangles.assign(all.begin(), all.begin() + 16);
        pack_triangle_blocks(
            16, [&](std::size_t k) { return l.triangles[k]; }, l.blocks);
        for (std::size_t k = 0; k < 16; ++k) l.corners[k] = make_triangle_corners(l.triangles[k]);
        std::mt19937 rng(2);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        for (int i = 0; i < 4096; ++i) {
            const Triangle& t = l.triangles[rng() % 16];
            const float a = unit(rng), b = unit(rng) * (1.0f - a);
            const glm::vec3 target = t.p0 + a * (t.p1 - t.p0) + b * (t.p2 - t.p0);
            const glm::vec3 org = 3.0f * target + glm::vec3(0.1f * unit(rng));
            l.rays.push_back({org, target - org, 0.0f, kInfinity});
        }
        return l;
    }();
    return l;
}

void leaf8(benchmark::State& state) {
    const Leaf& l = leaf();
    std::size_t i = 0;
    for (auto _ : state) {
        const Ray& ray = l.rays[i++ & 4095];
        const WatertightRay w = make_watertight_ray(ray);
        TriangleLanes8 lanes[2];
        for (int b = 0; b < 2; ++b)
            intersect_triangle8(w, l.blocks[b], 0xffu, ray.tmin, ray.tmax, lanes[b]);
        benchmark::DoNotOptimize(lanes);
    }
    state.SetItemsProcessed(16 * state.iterations());
}

void leaf_rays8(benchmark::State& state) {
    const Leaf& l = leaf();
    std::size_t i = 0;
    for (auto _ : state) {
        alignas(32) float lane[8][8];
        for (int r = 0; r < 8; ++r) {
            const Ray& ray = l.rays[(i + std::size_t(r)) & 4095];
            for (int a = 0; a < 3; ++a) {
                lane[a][r] = ray.org[a];
                lane[3 + a][r] = ray.dir[a];
            }
            lane[6][r] = ray.tmin;
            lane[7][r] = ray.tmax;
        }
        i += 8;
        const auto v = [&](int k) { return _mm256_load_ps(lane[k]); };
        const WatertightRays8 rays = make_watertight_rays8({v(0), v(1), v(2)}, {v(3), v(4), v(5)});
        TriangleLanes8 lanes[16];
        for (int k = 0; k < 16; ++k)
            intersect_rays8(rays, l.corners[k], v(6), v(7), 0xffu, lanes[k]);
        benchmark::DoNotOptimize(lanes);
    }
    state.SetItemsProcessed(128 * state.iterations());
}

void leaf_scalar(benchmark::State& state) {
    const Leaf& l = leaf();
    std::size_t i = 0;
    for (auto _ : state) {
        const Ray& ray = l.rays[i++ & 4095];
        const WatertightRay w = make_watertight_ray(ray);
        float t_far = ray.tmax;
        for (const Triangle& t : l.triangles) {
            TriangleHit hit;
            if (intersect_triangle(w, t, ray.tmin, t_far, hit)) t_far = hit.t;
        }
        benchmark::DoNotOptimize(t_far);
    }
    state.SetItemsProcessed(16 * state.iterations());
}

void partition_triangles(benchmark::State& state) {
    const auto& tris = data().triangles;
    const std::size_t n = tris.size();
    std::vector<glm::vec3> centroids;
    for (const Triangle& t : tris) centroids.push_back(centroid(t));
    std::vector<std::uint32_t> ids(n);
    PartitionScratch scratch;
    scratch.reserve(n);
    for (auto _ : state) {
        for (std::size_t i = 0; i < n; ++i) ids[i] = std::uint32_t(i);
        benchmark::DoNotOptimize(partition(ids.data(), n, scratch, [&](std::uint32_t t) {
            return bin_index((centroids[t].x + 1.0f) * 4.0f, 8) <= 3;
        }));
    }
    state.SetItemsProcessed(std::int64_t(n) * state.iterations());
}

void binning(benchmark::State& state) {
    const auto& tris = data().triangles;
    std::vector<glm::vec3> centroids;
    std::vector<Aabb> bounds;
    for (const Triangle& t : tris) {
        centroids.push_back(centroid(t));
        bounds.push_back(conservative_bounds(t));
    }
    BinAxis axis;
    BinAxis::make(0, -1.0f, 1.0f, 8, axis);
    std::vector<Bin> bins(8);
    std::vector<BinSplit> splits(7);
    for (auto _ : state) {
        fill_bins(
            bins, 0, tris.size(), [&](std::size_t i) { return axis(centroids[i]); },
            [&](std::size_t i) { return bounds[i]; }, tris.size() + 1);  // one thread
        sweep_bins(bins, splits);
        benchmark::DoNotOptimize(splits.data());
    }
    state.SetItemsProcessed(std::int64_t(tris.size()) * state.iterations());
}

BENCHMARK(filter_stream)->Arg(4096)->Arg(1 << 20)->UseRealTime();
BENCHMARK(filter_scalar)->Arg(4096)->Arg(1 << 20)->UseRealTime();
BENCHMARK(sampling8);
BENCHMARK(sampling_scalar);
BENCHMARK(leaf8);
BENCHMARK(leaf_rays8);
BENCHMARK(leaf_scalar);
BENCHMARK(binning);
BENCHMARK(partition_triangles)->UseRealTime();

}  // namespace
}  // namespace edacrt

BENCHMARK_MAIN();
