// The BVH's parts: the shared binning, the AVX2 box kernel against the scalar one, hits
// identical to naive on huge triangles and slivers, and a build that is the same for any thread
// count and keeps leaves small (and NaN-free) on flat, coincident and big-triangle input.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <random>

#include "geometry/binning.h"
#include "geometry/ray_box8.h"
#include "trace/bvh_build.h"
#include "trace/bvh_tracer.h"
#include "trace/naive_tracer.h"

namespace edacrt {
namespace {

Scene triangle_scene(const std::vector<Triangle>& triangles) {
    Scene scene;
    scene.source = "bvh test";
    for (const Triangle& t : triangles) {
        const std::uint32_t i = std::uint32_t(scene.positions.size());
        scene.positions.insert(scene.positions.end(), {t.p0, t.p1, t.p2});
        scene.triangles.push_back({i, i + 1, i + 2});
    }
    scene.triangle_materials.assign(scene.triangles.size(), 0);
    scene.materials.resize(1);
    return scene;
}

/// Huge triangles across the whole scene (a floor, walls, a tilted one), long slivers (aspect
/// up to 1e5) and small triangles.
std::vector<Triangle> huge_and_sliver_triangles(std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<Triangle> tris = {
        {{-10, -1, -10}, {10, -1, -10}, {10, -1, 10}},
        {{-10, -1, -10}, {10, -1, 10}, {-10, -1, 10}},
        {{-10, -1, -10}, {-10, 9, -10}, {10, 9, -10}},
        {{-9, -1, 9}, {9, 8, -9}, {9, -1, 9}},
    };
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 a(unit(rng) * 9, unit(rng) * 4 + 4, unit(rng) * 9);
        const glm::vec3 d = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)));
        const float width = std::pow(10.0f, -5.0f * (unit(rng) * 0.5f + 0.5f));
        tris.push_back({a - 8.0f * d, a + 8.0f * d, a + glm::vec3(0, width, 0)});
    }
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 c(unit(rng) * 9, unit(rng) * 4 + 4, unit(rng) * 9);
        tris.push_back({c, c + 0.2f * glm::vec3(unit(rng), unit(rng), unit(rng)),
                        c + 0.2f * glm::vec3(unit(rng), unit(rng), unit(rng))});
    }
    return tris;
}

TEST(Binning, BinsAndSweepsCountEveryItemOnce) {
    const std::vector<Aabb> boxes = {{{0, 0, 0}, {1, 1, 1}},
                                     {{2, 0, 0}, {3, 0, 0}},  // flat
                                     {{5, 0, 0}, {6, 1, 1}},
                                     {{9, 0, 0}, {10, 1, 1}}};
    BinAxis axis;
    ASSERT_TRUE(BinAxis::make(0, 0.5f, 9.5f, 4, axis));
    std::vector<Bin> bins(4);
    std::vector<BinSplit> splits(3);
    fill_bins(
        bins, 0, boxes.size(), [&](std::size_t i) { return axis(boxes[i].center()); },
        [&](std::size_t i) { return boxes[i]; });
    EXPECT_EQ(bins[0].count + bins[1].count + bins[2].count + bins[3].count, 4u);
    EXPECT_EQ(bins[0].count, 2u);  // 0.5 and 2.5 in [0.5, 2.75)
    EXPECT_EQ(bins[3].count, 1u);  // the upper end lands in the last bin
    sweep_bins(bins, splits);
    for (const BinSplit& s : splits) EXPECT_EQ(s.left_count + s.right_count, 4u);
    EXPECT_EQ(splits[0].left.hi.x, 3.0f);
    EXPECT_EQ(splits[0].left.surface_area(), 14.0f);  // the flat box adds no NaN
    EXPECT_EQ(splits[2].right.lo.x, 9.0f);
    BinAxis unused;
    EXPECT_FALSE(BinAxis::make(0, 1.0f, 1.0f, 4, unused));  // a point: nothing to separate
    EXPECT_FALSE(BinAxis::make(0, NAN, 1.0f, 4, unused));
}

TEST(Binning, ParallelBinsEqualSerialOnes) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Aabb> boxes(50000);
    for (Aabb& b : boxes) {
        b.extend(glm::vec3(unit(rng), unit(rng), unit(rng)));
        b.extend(glm::vec3(unit(rng), unit(rng), unit(rng)));
    }
    BinAxis axis;
    ASSERT_TRUE(BinAxis::make(1, 0.0f, 1.0f, 13, axis));
    std::vector<Bin> serial(13), parallel(13);
    const auto bin_of = [&](std::size_t i) { return axis(boxes[i].center()); };
    const auto box_of = [&](std::size_t i) { return boxes[i]; };
    fill_bins(serial, 0, boxes.size(), bin_of, box_of, boxes.size() + 1);
    fill_bins(parallel, 0, boxes.size(), bin_of, box_of, 1000);
    for (int k = 0; k < 13; ++k) {
        EXPECT_EQ(serial[k].count, parallel[k].count);
        EXPECT_EQ(serial[k].box.lo, parallel[k].box.lo);
        EXPECT_EQ(serial[k].box.hi, parallel[k].box.hi);
    }
}

/// Every lane of the AVX2 test decides as the scalar intersect_box, to the bit, on boxes and
/// rays that stress it: zero and -0 direction components, origins on slab planes, flat boxes,
/// unused lanes.
TEST(BoxKernel, EightLanesMatchTheScalarTest) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const auto coordinate = [&] {  // often exactly a plane value
        return rng() % 4 == 0 ? float(int(rng() % 3) - 1) : unit(rng) * 2.0f;
    };
    std::size_t hits = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Aabb scalar[8];
        const int used = 1 + int(rng() % 8);
        for (int lane = 0; lane < used; ++lane) {
            scalar[lane].extend(glm::vec3(coordinate(), coordinate(), coordinate()));
            scalar[lane].extend(glm::vec3(coordinate(), coordinate(), coordinate()));
        }
        const Boxes8 boxes = pack_boxes8(used, [&](int lane) { return scalar[lane]; });
        Ray ray{{coordinate(), coordinate(), coordinate()}, {unit(rng), unit(rng), unit(rng)}};
        for (int axis = 0; axis < 3; ++axis)
            if (rng() % 3 == 0) ray.dir[axis] = rng() % 2 ? 0.0f : -0.0f;
        if (ray.dir == glm::vec3(0.0f)) ray.dir.x = 1.0f;
        ray.tmin = rng() % 2 ? 0.0f : 0.5f * (unit(rng) + 1.0f);
        const float t_far = rng() % 2 ? kInfinity : 3.0f * (unit(rng) + 1.0f);
        const SlabRay sray = make_slab_ray(ray);
        __m256 t_entry;
        const int mask = intersect_boxes8(make_slab_ray1x8(sray), boxes, t_far, t_entry);
        alignas(32) float t[8];
        _mm256_store_ps(t, t_entry);
        for (int lane = 0; lane < 8; ++lane) {
            float expected_entry = 0.0f;
            const bool expected = intersect_box(sray, scalar[lane], t_far, expected_entry);
            ASSERT_EQ(bool(mask & (1 << lane)), expected) << "trial " << trial << " lane " << lane;
            if (lane >= used) {
                ASSERT_FALSE(expected);
            }
            if (!expected) continue;
            ++hits;
            ASSERT_EQ(std::memcmp(&t[lane], &expected_entry, sizeof(float)), 0);
        }
    }
    EXPECT_GT(hits, 5000u);
}

/// Rays from everywhere against huge triangles (whose boxes overlap every node) and slivers:
/// the same closest hits as naive, and the same occlusion answers.
TEST(Bvh, HugeTrianglesAndSliversGiveTheHitsOfNaive) {
    std::mt19937 rng(13);
    const Scene scene = triangle_scene(huge_and_sliver_triangles(rng));
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<Ray> rays;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 d(unit(rng), unit(rng), unit(rng));
        if (i % 5 == 0) d = {unit(rng) * 1e-3f, -1.0f, 0.0f};  // straight down at the floor
        if (glm::dot(d, d) < 1e-8f) d = {0, -1, 0};
        rays.push_back({{unit(rng) * 12, unit(rng) * 6 + 4, unit(rng) * 12}, glm::normalize(d)});
    }
    BvhTracer bvh;
    NaiveTracer naive;
    bvh.set_scene(scene);
    naive.set_scene(scene);
    std::vector<Hit> expected(rays.size()), got(rays.size());
    naive.trace(rays, expected, Query::closest);
    bvh.trace(rays, got, Query::closest);
    std::size_t hit_count = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ASSERT_EQ(got[i].prim >= 0, expected[i].prim >= 0) << "ray " << i;
        if (expected[i].prim < 0) continue;
        ++hit_count;
        ASSERT_EQ(got[i].t, expected[i].t) << "ray " << i;  // another prim only on a tie
    }
    EXPECT_GT(hit_count, rays.size() / 4);
    naive.trace(rays, expected, Query::any);
    bvh.trace(rays, got, Query::any);
    for (std::size_t i = 0; i < rays.size(); ++i)
        ASSERT_EQ(got[i].prim >= 0, expected[i].prim >= 0) << "ray " << i;
}

std::vector<BvhReference> soup_references(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<Triangle> tris;
    for (std::size_t i = 0; i < count; ++i) {
        const glm::vec3 c(unit(rng), unit(rng), unit(rng));
        const float size = i % 50 == 0 ? 1.0f : 0.02f;
        tris.push_back({c, c + size * glm::vec3(unit(rng), unit(rng), unit(rng)),
                        c + size * glm::vec3(unit(rng), unit(rng), unit(rng))});
    }
    std::vector<BvhReference> refs;
    for (std::uint32_t i = 0; i < tris.size(); ++i)
        refs.push_back({conservative_bounds(tris[i]), i});
    return refs;
}

TEST(BvhBuild, SameTreeForAnyThreadCount) {
    const std::vector<BvhReference> refs = soup_references(60000, 17);
    const auto build_with = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return build_bvh(refs);
    };
    const Bvh one = build_with(1), four = build_with(4);
    ASSERT_EQ(one.nodes.size(), four.nodes.size());
    EXPECT_EQ(std::memcmp(one.nodes.data(), four.nodes.data(), one.nodes.size() * sizeof(BvhNode)),
              0);
    EXPECT_EQ(one.prims, four.prims);
    EXPECT_TRUE(build_bvh({}).nodes.empty());
}

/// Leaves of at most max_leaf references, whatever the SAH says: a binary tree over n
/// references where every node larger than max_leaf is split.
void expect_small_leaves(const Bvh& bvh, std::uint32_t max_leaf, std::size_t references) {
    std::size_t in_leaves = 0;
    for (const BvhNode& node : bvh.nodes) {
        EXPECT_FALSE(std::isnan(node.box.surface_area()));
        if (node.count == 0) continue;
        EXPECT_LE(node.count, max_leaf);
        in_leaves += node.count;
    }
    EXPECT_EQ(in_leaves, references);
}

TEST(BvhBuild, CoincidentAndFlatInputIsSplitByTheMedian) {
    // 100 copies of one triangle: every centroid in one point, no SAH split exists.
    std::vector<BvhReference> same(100, BvhReference{{{0, 0, 0}, {1, 1, 0}}, 0});
    for (std::uint32_t i = 0; i < same.size(); ++i) same[i].prim = i;
    expect_small_leaves(build_bvh(same), BvhBuildOptions{}.max_leaf, same.size());
    // Flat boxes in one plane (zero areas) and points.
    std::vector<BvhReference> flat;
    for (std::uint32_t i = 0; i < 500; ++i) {
        const glm::vec3 p(float(i % 25), float(i / 25), 0.0f);
        flat.push_back({{p, i % 2 ? p : p + glm::vec3(0.5f, 0.5f, 0.0f)}, i});
    }
    expect_small_leaves(build_bvh(flat), BvhBuildOptions{}.max_leaf, flat.size());
}

TEST(BvhBuild, BigTrianglesNoLongerMakeHugeLeaves) {
    // The old build stopped at leaves of ~770 triangles in Sponza: big triangles made every
    // centroid split look worse than a leaf. Leaves are now bounded whatever the input.
    std::mt19937 rng(19);
    const std::vector<Triangle> tris = huge_and_sliver_triangles(rng);
    std::vector<BvhReference> refs;
    for (std::uint32_t i = 0; i < tris.size(); ++i)
        refs.push_back({conservative_bounds(tris[i]), i});
    expect_small_leaves(build_bvh(refs), BvhBuildOptions{}.max_leaf, refs.size());
}

}  // namespace
}  // namespace edacrt
