#pragma once
// The leaves of the divide-and-conquer recursion (edacrt_recursion.h): brute force, every ray of
// a range of the stream against every triangle of the leaf, eight lanes at a time in one of two
// shapes: each ray against blocks of eight triangles (trace_rays), or groups of eight rays
// against one triangle at a time (trace_ray_groups). Each ray gets the hits of the scalar loop
// over the leaf's triangles in order (triangle8.h hands back the lanes it cannot decide): a hit
// goes to the batch's hits (by ray id) and shortens the ray's t_far in the stream; an any-hit ray
// stops at its first hit (t_far = -inf) and is skipped from then on.
#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/simd8.h"
#include "geometry/triangle.h"
#include "geometry/triangle8.h"
#include "trace/ray_stream.h"
#include "trace/tracer.h"

namespace edacrt {

/// A leaf's triangles: tris[0 .. count) index the frame's triangles, whose scene triangles are
/// prims (the pieces of a pre-split triangle share theirs), indices into `triangles`.
struct LeafTriangles {
    const std::uint32_t* tris;
    std::size_t count;
    const Triangle* triangles;
    const std::uint32_t* prims;

    const Triangle& triangle(std::size_t k) const { return triangles[prims[tris[k]]]; }
    std::int32_t prim(std::size_t k) const { return std::int32_t(prims[tris[k]]); }
};

/// A leaf's triangles in the kernels' layouts; a thread's, reused by every leaf.
struct LeafScratch {
    std::vector<TriangleBlock8> blocks;    // for trace_rays
    std::vector<TriangleCorners> corners;  // for trace_ray_groups,
    std::vector<std::int32_t> prims;       // with the scene triangle of each

    void pack_blocks(const LeafTriangles& leaf) {
        blocks.resize(std::max(blocks.size(), (leaf.count + 7) / 8));
        pack_triangle_blocks(
            leaf.count, [&](std::size_t k) { return leaf.triangle(k); }, blocks);
    }

    void pack_corners(const LeafTriangles& leaf) {
        corners.resize(std::max(corners.size(), leaf.count));
        prims.resize(std::max(prims.size(), leaf.count));
        for (std::size_t k = 0; k < leaf.count; ++k) {
            prims[k] = leaf.prim(k);
            corners[k] = make_triangle_corners(leaf.triangle(k));
        }
    }

    std::size_t bytes() const {
        return blocks.capacity() * sizeof(TriangleBlock8) +
               corners.capacity() * sizeof(TriangleCorners) +
               prims.capacity() * sizeof(std::int32_t);
    }
};

/// The kernels' statistics hooks, empty. A recording one (the recursion's) sees each hit
/// (`hit`, with the ray's id) and each traced ray's triangle tests (`traced`); large leaves call
/// them from worker threads, each with its own rays.
struct NullLeafObserver {
    void hit(std::uint32_t) const {}
    void traced(std::uint32_t, std::uint32_t) const {}
};

/// A closest-hit ray skips the triangle it has already hit (another piece of a pre-split
/// triangle, in this leaf or a later one), which for a large triangle near the eye (a loose
/// float distance bound) saves a double-precision refinement. The test depends only on the
/// ray, the triangle and [tmin, t_far], and t_far is that hit's t (a ray's t_far changes only
/// with its hit, RayStream), so the re-test either rejects or accepts the identical t, u, v:
/// either way the hit stays. A tie with another triangle in between makes that one the current
/// hit, and the re-test then runs as before. A skipped pair still counts as a triangle test in
/// the statistics (the leaf examined it).
template <Query Q>
inline constexpr bool kSkipsCurrentHit = Q == Query::closest;

/// trace_rays prefetches the hit this many rays ahead.
inline constexpr std::size_t kPrefetchRays = 4;

/// Prefetches the hits of the rays at stream positions [begin, end), which a leaf reads (a
/// closest-hit ray's current hit) and writes on a hit, so that the access by ray number,
/// random in incoherent sets, overlaps the tests of the rays before them.
inline void prefetch_hits(const RayBatch& batch, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i != end; ++i)
        _mm_prefetch(reinterpret_cast<const char*>(&batch.hits[batch.stream.id[i]]), _MM_HINT_T0);
}

/// A lane of the 8-wide test: the float path's hit if within the current t_far, or the scalar
/// test's verdict where the float path handed the lane back.
inline bool resolve(const TriangleLanes8& lanes, int lane, const WatertightRay& wray,
                    const Triangle& tri, float tmin, float t_far, TriangleHit& hit) {
    if ((lanes.scalar >> lane) & 1) return intersect_triangle(wray, tri, tmin, t_far, hit);
    if (!(lanes.t[lane] <= t_far)) return false;
    hit = {lanes.t[lane], lanes.v[lane] * lanes.inv_det[lane], lanes.w[lane] * lanes.inv_det[lane]};
    return true;
}

/// The rays at stream positions [begin, end), one at a time, against eight triangles at a time
/// (`blocks`: the leaf's triangles packed by LeafScratch::pack_blocks). Returns the triangle
/// tests.
template <Query Q, class LeafObserver>
std::uint64_t trace_rays(const RayBatch& batch, std::size_t begin, std::size_t end,
                         const LeafTriangles& leaf, std::span<const TriangleBlock8> blocks,
                         const LeafObserver& observer) {
    const RayStream& stream = batch.stream;
    const std::size_t block_count = (leaf.count + 7) / 8;
    const unsigned last_valid = 0xffu >> (block_count * 8 - leaf.count);
    std::uint64_t tests = 0;
    for (std::size_t i = begin; i != end; ++i) {
        prefetch_hits(batch, std::min(i + kPrefetchRays, end),
                      std::min(i + kPrefetchRays + 1, end));
        float& t_far = stream.t_far[i];
        if (Q == Query::any && t_far == -kInfinity) continue;
        const std::uint32_t r = stream.id[i];
        const float tmin = stream.tmin[i];
        const WatertightRay wray = make_watertight_ray(stream.ray(i));
        std::int32_t current = kSkipsCurrentHit<Q> ? batch.hits[r].prim : -1;
        std::size_t tested = leaf.count;
        for (std::size_t b = 0; b < block_count && tested == leaf.count; ++b) {
            TriangleLanes8 lanes;
            intersect_triangle8(wray, blocks[b], b + 1 < block_count ? 0xffu : last_valid, tmin,
                                t_far, lanes);
            // In triangle order, as the scalar loop: t_far shrinks with each hit.
            for (unsigned pending = lanes.accepted | lanes.scalar; pending;
                 pending &= pending - 1) {
                const int lane = std::countr_zero(pending);
                const std::size_t k = 8 * b + std::size_t(lane);
                TriangleHit hit;
                if ((kSkipsCurrentHit<Q> && leaf.prim(k) == current) ||
                    !resolve(lanes, lane, wray, leaf.triangle(k), tmin, t_far, hit))
                    continue;
                batch.hits[r] = {hit.t, leaf.prim(k), hit.u, hit.v};
                observer.hit(r);
                if constexpr (kSkipsCurrentHit<Q>) current = leaf.prim(k);
                if constexpr (Q == Query::any) {
                    t_far = -kInfinity;
                    tested = k + 1;
                    break;
                }
                t_far = hit.t;
            }
        }
        observer.traced(r, std::uint32_t(tested));
        tests += tested;
    }
    return tests;
}

/// The rays at stream positions [begin, end) in groups of eight (the last may be short), each
/// group against one triangle at a time (`corners` and `prims`: the leaf's triangles packed by
/// LeafScratch::pack_corners). Each lane does what trace_rays does for its ray: a hit shortens
/// its t_far for the next triangle, and an any-hit ray stops at its first hit. Returns the
/// triangle tests.
template <Query Q, class LeafObserver>
std::uint64_t trace_ray_groups(const RayBatch& batch, std::size_t begin, std::size_t end,
                               const LeafTriangles& leaf, std::span<const TriangleCorners> corners,
                               std::span<const std::int32_t> prims, const LeafObserver& observer) {
    using simd8::lane_mask;
    const RayStream& stream = batch.stream;
    std::uint64_t tests = 0;
    for (std::size_t i = begin; i < end; i += 8) {
        const int n = int(std::min<std::size_t>(8, end - i));
        prefetch_hits(batch, std::min(i + 8, end), std::min(i + 16, end));
        const __m256i in_group =
            _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        const auto load = [&](const float* a) { return _mm256_maskload_ps(a + i, in_group); };
        const __m256 org[3] = {load(stream.org[0]), load(stream.org[1]), load(stream.org[2])};
        const __m256 dir[3] = {load(stream.dir[0]), load(stream.dir[1]), load(stream.dir[2])};
        const WatertightRays8 rays = make_watertight_rays8(org, dir);
        const __m256 tmin = load(stream.tmin);
        // Each lane's t_far, and its hit: the triangle's place in the leaf (-1: none), u, v.
        alignas(32) float t_far[8], u[8] = {}, v[8] = {};
        alignas(32) std::int32_t hit[8], current[8];  // current: see kSkipsCurrentHit
        _mm256_store_ps(t_far, load(stream.t_far));
        std::fill_n(hit, 8, -1);
        for (int l = 0; l < 8; ++l)
            current[l] =
                kSkipsCurrentHit<Q> && l < n ? batch.hits[stream.id[i + std::size_t(l)]].prim : -1;
        unsigned active = (1u << n) - 1;
        if constexpr (Q == Query::any)
            active &= ~unsigned(_mm256_movemask_ps(
                _mm256_cmp_ps(_mm256_load_ps(t_far), _mm256_set1_ps(-kInfinity), _CMP_EQ_OQ)));
        const unsigned traced = active;
        std::uint32_t tested[8];
        std::fill_n(tested, 8, std::uint32_t(leaf.count));
        for (std::size_t k = 0; k < leaf.count && active; ++k) {
            const std::int32_t prim = prims[k];
            unsigned candidates = active;
            if constexpr (kSkipsCurrentHit<Q>)
                candidates &= ~unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(
                    _mm256_cmpeq_epi32(_mm256_set1_epi32(prim),
                                       _mm256_load_si256(reinterpret_cast<__m256i*>(current))))));
            if (!candidates) continue;
            TriangleLanes8 lanes;
            intersect_rays8(rays, corners[k], tmin, _mm256_load_ps(t_far), candidates, lanes);
            unsigned hits = 0;
            if (lanes.accepted) {  // t <= t_far: the lane's ray hits nearer
                const __m256 take = lane_mask(lanes.accepted);
                const __m256 inv_det = _mm256_load_ps(lanes.inv_det);
                const auto update = [&](float* to, __m256 value) {
                    _mm256_store_ps(to, _mm256_blendv_ps(_mm256_load_ps(to), value, take));
                };
                update(t_far, _mm256_load_ps(lanes.t));
                update(u, _mm256_mul_ps(_mm256_load_ps(lanes.v), inv_det));
                update(v, _mm256_mul_ps(_mm256_load_ps(lanes.w), inv_det));
                update(reinterpret_cast<float*>(hit),
                       _mm256_castsi256_ps(_mm256_set1_epi32(std::int32_t(k))));
                update(reinterpret_cast<float*>(current),
                       _mm256_castsi256_ps(_mm256_set1_epi32(prim)));
                hits = lanes.accepted;
            }
            for (unsigned pending = lanes.scalar; pending; pending &= pending - 1) {
                const int l = std::countr_zero(pending);
                const WatertightRay wray = make_watertight_ray(stream.ray(i + std::size_t(l)));
                TriangleHit h;
                if (!intersect_triangle(wray, leaf.triangle(k), stream.tmin[i + std::size_t(l)],
                                        t_far[l], h))
                    continue;
                t_far[l] = h.t, u[l] = h.u, v[l] = h.v, hit[l] = std::int32_t(k);
                current[l] = prim;
                hits |= 1u << l;
            }
            if constexpr (Q == Query::any) {
                for (unsigned done = hits; done; done &= done - 1)
                    tested[std::countr_zero(done)] = std::uint32_t(k + 1);
                active &= ~hits;
            }
        }
        for (unsigned lanes = traced; lanes; lanes &= lanes - 1) {
            const int l = std::countr_zero(lanes);
            const std::uint32_t r = stream.id[i + std::size_t(l)];
            if (hit[l] >= 0) {
                batch.hits[r] = {t_far[l], prims[std::size_t(hit[l])], u[l], v[l]};
                observer.hit(r);
                stream.t_far[i + std::size_t(l)] = Q == Query::any ? -kInfinity : t_far[l];
            }
            observer.traced(r, tested[l]);
            tests += tested[l];
        }
    }
    return tests;
}

}  // namespace edacrt
