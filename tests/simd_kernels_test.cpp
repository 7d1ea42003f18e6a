// The AVX2 kernels against the scalar tests they replace, bit for bit, on random and
// adversarial inputs: the slab test on eight lanes (intersect_box8), the triangle test on
// eight triangles and on eight rays (intersect_triangle8, intersect_rays8: what they decide
// must be what intersect_triangle decides, and they may hand any lane back), the leaf kernels
// built on them (trace_rays, trace_ray_groups: the scalar loop's hits), and the in-place filter
// (filter_rays), sequential and in parallel blocks.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <random>
#include <vector>

#include "geometry/ray_box8.h"
#include "geometry/triangle8.h"
#include "trace/leaf_kernels.h"
#include "trace/ray_filter.h"
#include "trace/ray_stream.h"

namespace edacrt {
namespace {

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Coordinates that stress the tests: zeros of both signs, values on a small lattice (so
/// origins land on box planes and corners coincide), tiny, huge and ordinary ones.
float awkward(std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    switch (rng() % 8) {
        case 0:
            return 0.0f;
        case 1:
            return -0.0f;
        case 2:
            return float(int(rng() % 5) - 2);  // lattice: planes, shared corners
        case 3:
            return unit(rng) * 1e-30f;
        case 4:
            return unit(rng) * 1e30f;
        case 5:
            return unit(rng) * 1e-6f + 1.0f;
        default:
            return unit(rng) * 4.0f;
    }
}

glm::vec3 awkward3(std::mt19937& rng) { return {awkward(rng), awkward(rng), awkward(rng)}; }

Ray awkward_ray(std::mt19937& rng) {
    Ray ray;
    ray.org = awkward3(rng);
    do ray.dir = awkward3(rng);
    while (ray.dir == glm::vec3(0.0f));
    ray.tmin = rng() % 4 == 0 ? std::abs(awkward(rng)) : 0.0f;
    ray.tmax = rng() % 3 == 0 ? kInfinity : ray.tmin + std::abs(awkward(rng));
    return ray;
}

Aabb awkward_box(std::mt19937& rng) {
    if (rng() % 16 == 0) return Aabb{};  // empty, as a padding lane
    Aabb box;
    box.extend(awkward3(rng));
    box.extend(rng() % 8 == 0 ? box.lo : awkward3(rng));  // some boxes are flat or points
    return box;
}

TEST(SimdKernels, SlabTestOnEightLanesIsTheScalarTestBitForBit) {
    std::mt19937 rng(7);
    int passed = 0;
    for (int round = 0; round < 20000; ++round) {
        Ray rays[8];
        Aabb boxes[8];
        float t_far[8];
        alignas(32) float lane[14][8];
        for (int l = 0; l < 8; ++l) {
            rays[l] = awkward_ray(rng);
            boxes[l] = awkward_box(rng);
            t_far[l] = rng() % 16 == 0 ? -kInfinity : rays[l].tmax;  // a finished any-hit ray
            const SlabRay s = make_slab_ray(rays[l]);
            for (int k = 0; k < 3; ++k) {
                lane[k][l] = s.org[k];
                lane[3 + k][l] = s.inv_dir[k];
                lane[8 + k][l] = boxes[l].lo[k];
                lane[11 + k][l] = boxes[l].hi[k];
            }
            lane[6][l] = s.tmin;
            lane[7][l] = t_far[l];
        }
        const auto v = [&](int k) { return _mm256_load_ps(lane[k]); };
        const SlabRay8 ray8{{v(0), v(1), v(2)}, {v(3), v(4), v(5)}, v(6), v(7)};
        const Aabb8 box8{{v(8), v(9), v(10)}, {v(11), v(12), v(13)}};
        __m256 entry8;
        const unsigned mask = unsigned(_mm256_movemask_ps(intersect_box8(ray8, box8, entry8)));
        alignas(32) float entries[8];
        _mm256_store_ps(entries, entry8);
        for (int l = 0; l < 8; ++l) {
            float entry;
            const bool hit = intersect_box(make_slab_ray(rays[l]), boxes[l], t_far[l], entry);
            ASSERT_EQ(hit, ((mask >> l) & 1) != 0) << "round " << round << " lane " << l;
            ASSERT_TRUE(same_bits(entry, entries[l])) << entry << " vs " << entries[l];
            passed += hit;
        }
    }
    EXPECT_GT(passed, 10000);  // both outcomes are well represented
    EXPECT_LT(passed, 150000);
}

/// Triangles that stress the triangle test: shared lattice corners (rays through edges and
/// vertices), slivers, degenerate ones, huge and tiny ones.
Triangle awkward_triangle(std::mt19937& rng) {
    Triangle tri{awkward3(rng), awkward3(rng), awkward3(rng)};
    switch (rng() % 6) {
        case 0:
            tri.p2 = tri.p1;
            break;  // degenerate
        case 1:
            tri.p2 = tri.p0 + (tri.p1 - tri.p0) * 0.5f + 1e-6f;
            break;  // sliver
        default:
            break;
    }
    return tri;
}

/// A corner of `tri`, a point on an edge or its centre: where rays test the edge rules.
glm::vec3 aim_point(const Triangle& tri, std::mt19937& rng) {
    const float w0 = float(rng() % 3) / 2.0f, w1 = float(rng() % 3) / 2.0f;
    return tri.p0 + w0 * (tri.p1 - tri.p0) + w1 * (tri.p2 - tri.p0);
}

/// What the eight-lane test decided for lane l, against the scalar test of the same pair:
/// a lane it decided must match intersect_triangle bit for bit; a lane it handed back is
/// counted.
struct LaneOutcomes {
    int accepted = 0, rejected = 0, handed_back = 0;
};

void check_lane(const TriangleLanes8& lanes, unsigned valid, int l, const WatertightRay& wray,
                const Triangle& tri, const Ray& ray, LaneOutcomes& outcomes) {
    if (!((valid >> l) & 1) || ((lanes.scalar >> l) & 1)) {
        outcomes.handed_back += (lanes.scalar >> l) & 1;
        return;
    }
    TriangleHit hit;
    const bool scalar = intersect_triangle(wray, tri, ray.tmin, ray.tmax, hit);
    ASSERT_EQ(scalar, ((lanes.accepted >> l) & 1) != 0);
    if (!scalar) {
        ++outcomes.rejected;
        return;
    }
    ++outcomes.accepted;
    ASSERT_TRUE(same_bits(hit.t, lanes.t[l]));
    ASSERT_TRUE(same_bits(hit.u, lanes.v[l] * lanes.inv_det[l]));
    ASSERT_TRUE(same_bits(hit.v, lanes.w[l] * lanes.inv_det[l]));
}

TEST(SimdKernels, TriangleTestOnEightLanesDecidesOnlyWhatTheScalarTestDecides) {
    std::mt19937 rng(11);
    LaneOutcomes outcomes;
    for (int round = 0; round < 40000; ++round) {
        // Rays aimed at a triangle's corner, edge or inside, or anywhere.
        Triangle tris[8];
        for (Triangle& tri : tris) tri = awkward_triangle(rng);
        TriangleBlock8 block;
        pack_triangle_blocks(8, [&](std::size_t l) { return tris[l]; }, {&block, 1});
        Ray ray = awkward_ray(rng);
        const Triangle& target = tris[rng() % 8];
        const glm::vec3 aim = aim_point(target, rng);
        if (rng() % 2 && aim != ray.org) ray.dir = aim - ray.org;
        const WatertightRay wray = make_watertight_ray(ray);
        const unsigned valid = rng() % 4 == 0 ? unsigned(rng() % 256) : 0xffu;
        TriangleLanes8 lanes;
        intersect_triangle8(wray, block, valid, ray.tmin, ray.tmax, lanes);
        ASSERT_EQ(lanes.accepted & lanes.scalar, 0u);
        ASSERT_EQ((lanes.accepted | lanes.scalar) & ~valid, 0u);
        for (int l = 0; l < 8; ++l)
            ASSERT_NO_FATAL_FAILURE(check_lane(lanes, valid, l, wray, tris[l], ray, outcomes))
                << "round " << round << " lane " << l;
    }
    // The float path decides most lanes; the awkward ones go back to the scalar test.
    // (The awkward corners lie far from the rays' origins, beyond 2^20 of the sheared
    // coordinates, where the corners' rounding leaves the float sign undecided: most lanes.)
    EXPECT_GT(outcomes.accepted, 1000);
    EXPECT_GT(outcomes.rejected, 50000);
    EXPECT_GT(outcomes.handed_back, 1000);
}

TEST(SimdKernels, EightRaysAgainstOneTriangleDecideOnlyWhatTheScalarTestDecides) {
    std::mt19937 rng(13);
    LaneOutcomes outcomes;
    for (int round = 0; round < 40000; ++round) {
        const Triangle tri = awkward_triangle(rng);
        const TriangleCorners corners = make_triangle_corners(tri);
        // Eight rays of any directions (so lanes differ in their axes), most aimed at the
        // triangle's corners, edges or inside.
        Ray rays[8];
        alignas(32) float lane[8][8];
        for (int l = 0; l < 8; ++l) {
            Ray& ray = rays[l];
            ray = awkward_ray(rng);
            const glm::vec3 aim = aim_point(tri, rng);
            if (rng() % 4 != 0 && aim != ray.org) ray.dir = aim - ray.org;
            for (int a = 0; a < 3; ++a) {
                lane[a][l] = ray.org[a];
                lane[3 + a][l] = ray.dir[a];
            }
            lane[6][l] = ray.tmin;
            lane[7][l] = ray.tmax;
        }
        const auto v = [&](int k) { return _mm256_load_ps(lane[k]); };
        const WatertightRays8 rays8 = make_watertight_rays8({v(0), v(1), v(2)}, {v(3), v(4), v(5)});
        alignas(32) std::int32_t k[3][8];
        alignas(32) float sx[8], sy[8], sz[8];
        for (int a = 0; a < 3; ++a)
            _mm256_store_si256(reinterpret_cast<__m256i*>(k[a]), rays8.k[a]);
        _mm256_store_ps(sx, rays8.sx);
        _mm256_store_ps(sy, rays8.sy);
        _mm256_store_ps(sz, rays8.sz);
        const unsigned valid = rng() % 4 == 0 ? unsigned(rng() % 256) : 0xffu;
        TriangleLanes8 lanes;
        intersect_rays8(rays8, corners, v(6), v(7), valid, lanes);
        ASSERT_EQ(lanes.accepted & lanes.scalar, 0u);
        ASSERT_EQ((lanes.accepted | lanes.scalar) & ~valid, 0u);
        for (int l = 0; l < 8; ++l) {
            const WatertightRay wray = make_watertight_ray(rays[l]);
            ASSERT_EQ(k[0][l], wray.kx);
            ASSERT_EQ(k[1][l], wray.ky);
            ASSERT_EQ(k[2][l], wray.kz);
            ASSERT_TRUE(same_bits(sx[l], wray.sx) && same_bits(sy[l], wray.sy) &&
                        same_bits(sz[l], wray.sz));
            ASSERT_NO_FATAL_FAILURE(check_lane(lanes, valid, l, wray, tri, rays[l], outcomes))
                << "round " << round << " lane " << l;
        }
    }
    EXPECT_GT(outcomes.accepted, 400);  // (see above: the awkward corners)
    EXPECT_GT(outcomes.rejected, 30000);
    EXPECT_GT(outcomes.handed_back, 1000);
}

/// Both leaf kernels on the rays at stream positions [begin, end) against the scalar loop over
/// the leaf's triangles in order: the same hits to the bit, the same t_far left in the stream,
/// the same triangle tests. Adds the rays the scalar loop found a hit for to `found`.
template <Query Q>
void check_leaf_kernels(const std::vector<Ray>& rays, const LeafTriangles& leaf, std::size_t begin,
                        std::size_t end, int& found) {
    std::vector<Hit> expected(rays.size());
    std::uint64_t expected_tests = 0;
    for (std::size_t i = begin; i != end; ++i) {
        const Ray& ray = rays[i];
        if (Q == Query::any && ray.tmax == -kInfinity) continue;  // finished
        const WatertightRay wray = make_watertight_ray(ray);
        float t_far = ray.tmax;
        std::size_t tests = leaf.count;
        for (std::size_t k = 0; k < leaf.count; ++k) {
            TriangleHit h;
            if (!intersect_triangle(wray, leaf.triangle(k), ray.tmin, t_far, h)) continue;
            expected[i] = {h.t, leaf.prim(k), h.u, h.v};
            t_far = h.t;
            if (Q == Query::any) {
                tests = k + 1;
                break;
            }
        }
        found += expected[i].hit();
        expected_tests += tests;
    }
    for (const bool groups : {false, true}) {
        RayStreamStorage storage;
        std::vector<Hit> hits(rays.size());
        const RayBatch batch{storage.fill(rays), hits.data()};
        LeafScratch scratch;
        std::uint64_t tests;
        if (groups) {
            scratch.pack_corners(leaf);
            tests = trace_ray_groups<Q>(batch, begin, end, leaf, scratch.corners, scratch.prims,
                                        NullLeafObserver{});
        } else {
            scratch.pack_blocks(leaf);
            tests = trace_rays<Q>(batch, begin, end, leaf, scratch.blocks, NullLeafObserver{});
        }
        EXPECT_EQ(tests, expected_tests) << (groups ? "groups" : "rays");
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const Hit& a = hits[i];
            const Hit& b = expected[i];
            ASSERT_EQ(a.prim, b.prim) << (groups ? "groups" : "rays") << ", ray " << i;
            ASSERT_TRUE(same_bits(a.t, b.t) && same_bits(a.u, b.u) && same_bits(a.v, b.v));
            const float t_far = !b.hit() ? rays[i].tmax : Q == Query::any ? -kInfinity : b.t;
            ASSERT_TRUE(same_bits(batch.stream.t_far[i], t_far)) << "ray " << i;
        }
    }
}

TEST(SimdKernels, LeafKernelsFindTheScalarLoopsHitsInBothShapes) {
    std::mt19937 rng(17);
    int found = 0;
    for (const std::size_t tri_count : {1, 5, 8, 9, 16, 23}) {
        for (const std::size_t n : {1, 7, 8, 13, 40}) {
            for (int round = 0; round < 30; ++round) {
                std::vector<Triangle> triangles(tri_count);
                for (Triangle& tri : triangles) tri = awkward_triangle(rng);
                // The leaf lists the frame's triangles in an order of its own, and they are
                // the scene's in another.
                std::vector<std::uint32_t> tris(tri_count), prims(tri_count);
                for (std::size_t k = 0; k < tri_count; ++k) {
                    tris[k] = std::uint32_t(tri_count - 1 - k);
                    prims[k] = std::uint32_t((k + 3) % tri_count);
                }
                const LeafTriangles leaf{tris.data(), tri_count, triangles.data(), prims.data()};
                // Rays mostly aimed at a triangle's corner, edge or inside; some finished.
                std::vector<Ray> rays(n);
                for (Ray& ray : rays) {
                    ray = awkward_ray(rng);
                    const Triangle& target = triangles[rng() % tri_count];
                    const glm::vec3 aim = aim_point(target, rng);
                    if (rng() % 4 != 0 && aim != ray.org) ray.dir = aim - ray.org;
                    if (rng() % 16 == 0) ray.tmax = -kInfinity;
                }
                const std::size_t begin = n > 2 ? rng() % 3 : 0;
                ASSERT_NO_FATAL_FAILURE(
                    check_leaf_kernels<Query::closest>(rays, leaf, begin, n, found));
                ASSERT_NO_FATAL_FAILURE(
                    check_leaf_kernels<Query::any>(rays, leaf, begin, n, found));
            }
        }
    }
    EXPECT_GT(found, 1000);
}

/// A stream of `n` awkward rays, some already finished (t_far = -inf).
struct TestStream {
    RayStreamStorage storage;
    std::vector<Ray> rays;
    RayStream stream;
    TestStream(std::size_t n, std::mt19937& rng) {
        for (std::size_t i = 0; i < n; ++i) rays.push_back(awkward_ray(rng));
        stream = storage.fill(rays);
        for (std::size_t i = 0; i < n; ++i)
            if (rng() % 16 == 0) stream.t_far[i] = -kInfinity;
    }
    bool passes(std::uint32_t id, float t_far, const Aabb& box) const {
        float entry;
        return intersect_box(make_slab_ray(rays[id]), box, t_far, entry);
    }
};

TEST(SimdKernels, FilterMovesExactlyThePassingRaysToTheFrontAndKeepsEveryRayWhole) {
    std::mt19937 rng(3);
    // Ranges are [1, n - 1) for n > 2: 16, 24, 32 and 40 rays (n = 18, ...) make both ends'
    // lookahead windows cover the same blocks.
    for (const std::size_t n :
         {0, 1, 7, 8, 15, 16, 17, 18, 23, 24, 26, 31, 34, 42, 100, 1000, 32768, 70001}) {
        for (int round = 0; round < (n > 1000 ? 4 : 40); ++round) {
            TestStream s(n, rng);
            // A box around part of the scene, or all of it, or none.
            Aabb box = awkward_box(rng);
            if (round % 10 == 1) box = {glm::vec3(-1e38f), glm::vec3(1e38f)};
            std::vector<float> t_far(n);
            for (std::size_t i = 0; i < n; ++i) t_far[s.stream.id[i]] = s.stream.t_far[i];
            const std::size_t begin = n > 2 ? 1 : 0, count = n - begin - (n > 2 ? 1 : 0);
            const std::size_t passed = filter_rays(s.stream, begin, count, box);
            // Again on its own result: blocks that all pass or all miss (coherent rays).
            if (round % 2 == 1) {
                ASSERT_EQ(filter_rays(s.stream, begin, count, box), passed);
            }
            if (round % 4 == 3) {
                ASSERT_EQ(filter_rays(s.stream, begin + passed, count - passed, box), 0u);
            }
            std::vector<bool> seen(n, false);
            for (std::size_t i = 0; i < n; ++i) {
                const std::uint32_t id = s.stream.id[i];
                ASSERT_LT(id, n);
                ASSERT_FALSE(seen[id]) << "ray " << id << " twice";
                seen[id] = true;
                // Every field moved with its id.
                const SlabRay slab = make_slab_ray(s.rays[id]);
                const SlabRay moved = s.stream.slab_ray(i);
                for (int k = 0; k < 3; ++k) {
                    ASSERT_TRUE(same_bits(moved.org[k], slab.org[k]));
                    ASSERT_TRUE(same_bits(moved.inv_dir[k], slab.inv_dir[k]));
                    ASSERT_TRUE(same_bits(s.stream.dir[k][i], s.rays[id].dir[k]));
                }
                ASSERT_EQ(moved.tmin, slab.tmin);
                ASSERT_TRUE(same_bits(s.stream.t_far[i], t_far[id]));
                if (i < begin || i >= begin + count) {
                    ASSERT_EQ(id, i) << "a ray outside the range moved";
                    continue;
                }
                ASSERT_EQ(s.passes(id, t_far[id], box), i < begin + passed)
                    << "n " << n << " position " << i;
            }
        }
    }
}

TEST(SimdKernels, ParallelFilterGivesTheSameOrderForAnyThreadCount) {
    std::mt19937 rng(5);
    TestStream a(100000, rng);
    std::mt19937 same(5);
    TestStream b(100000, same);
    const Aabb box{glm::vec3(-1.0f), glm::vec3(1.5f)};
    std::size_t passed_a, passed_b;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        passed_a = filter_rays(a.stream, 0, 100000, box);
    }
    passed_b = filter_rays(b.stream, 0, 100000, box);
    EXPECT_EQ(passed_a, passed_b);
    EXPECT_GT(passed_a, 1000u);
    EXPECT_TRUE(std::equal(a.stream.id, a.stream.id + 100000, b.stream.id));
}

}  // namespace
}  // namespace edacrt
