#pragma once
// intersect_triangle (triangle.h) with AVX2, for one ray against eight triangles or eight rays
// against one triangle, bit for bit:
// the float path's operations in the same order (max_ps with swapped operands is std::max),
// and every lane the float path cannot decide alone (an uncertain edge, an untrusted
// distance) handed back to the scalar test, which then takes its double-precision path. The
// callers resolve the lanes in each ray's triangle order, so their hits are those of the
// scalar loop.
#include <immintrin.h>

#include <cstddef>
#include <span>

#include "geometry/simd8.h"
#include "geometry/triangle.h"

namespace edacrt {

/// Eight triangles' corners: p[corner][axis][lane].
struct TriangleBlock8 {
    alignas(32) float p[3][3][8];
};

inline void set_lane(TriangleBlock8& block, int lane, const Triangle& tri) {
    const glm::vec3* corners[3] = {&tri.p0, &tri.p1, &tri.p2};
    for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) block.p[c][a][lane] = (*corners[c])[a];
}

/// Packs triangle(0) .. triangle(count - 1) for intersect_triangle8: triangle k in lane k % 8
/// of blocks[k / 8]. The last block's spare lanes hold zero triangles, which callers leave out
/// of `valid`. `blocks` holds at least (count + 7) / 8 blocks.
template <class TriangleAt>
void pack_triangle_blocks(std::size_t count, const TriangleAt& triangle,
                          std::span<TriangleBlock8> blocks) {
    for (std::size_t k = 0; k < (count + 7) / 8 * 8; ++k)
        set_lane(blocks[k / 8], int(k % 8), k < count ? triangle(k) : Triangle{});
}

/// What the float path decided for eight triangles.
struct TriangleLanes8 {
    unsigned accepted = 0;  // a hit at t in [tmin, tmax], barycentrics v, w times inv_det
    unsigned scalar = 0;    // undecided: the caller runs intersect_triangle on these
    alignas(32) float t[8], v[8], w[8], inv_det[8];
};

/// Eight ray/triangle pairs in their rays' frames (shear_triangle's x, y, z of the corners
/// A, B, C), with the rays' |dir[kx]|, |dir[ky]| for the distance error bound.
struct ShearedTriangles8 {
    __m256 x[3], y[3], z[3];
    __m256 shear_x, shear_y;
};

/// The float path of intersect_triangle from the sheared corners on: the lanes of `valid` it
/// decides and those it hands back.
[[gnu::always_inline]] inline void decide_triangles8(const ShearedTriangles8& s, __m256 tmin,
                                                     __m256 tmax, unsigned valid,
                                                     TriangleLanes8& out) {
    using namespace simd8;
    const __m256(&x)[3] = s.x;
    const __m256(&y)[3] = s.y;
    const __m256(&z)[3] = s.z;
    // Edge functions U = C x B, V = A x C, W = B x A, each as the difference of two products.
    const __m256 pu = mul(x[2], y[1]), qu = mul(y[2], x[1]);
    const __m256 pv = mul(x[0], y[2]), qv = mul(y[0], x[2]);
    const __m256 pw = mul(x[1], y[0]), qw = mul(y[1], x[0]);
    const __m256 u = sub(pu, qu), v = sub(pv, qv), w = sub(pw, qw);
    // corner_error of each corner, then edge_uncertain of each edge.
    const __m256 shear = add(s.shear_x, s.shear_y);
    __m256 corner_error[3], corner_size[3];
    for (int c = 0; c < 3; ++c) {
        const __m256 xy = add(abs(x[c]), abs(y[c]));
        corner_error[c] = mul(set(0x1p-20f), add(xy, mul(shear, abs(z[c]))));
        corner_size[c] = add(xy, corner_error[c]);
    }
    const auto uncertain = [&](__m256 e, int p, int q) {
        const __m256 bound =
            max(add(mul(corner_error[p], corner_size[q]), mul(corner_error[q], corner_size[p])),
                set(0x1p-100f));
        const __m256 magnitude = abs(e);
        return any(cmp<_CMP_NGT_UQ>(magnitude, bound), cmp<_CMP_NLT_UQ>(magnitude, set(kInfinity)));
    };
    const __m256 zero = _mm256_setzero_ps();
    // separated_from_ray: corners beyond twice their error on one side of x = 0 or y = 0.
    __m256 margin[3], below[3];
    for (int c = 0; c < 3; ++c) {
        margin[c] = add(corner_error[c], corner_error[c]);
        below[c] = sub(zero, margin[c]);
    }
    const auto beyond = [&](const __m256(&p)[3]) {
        return any(all(cmp<_CMP_GT_OQ>(p[0], margin[0]), cmp<_CMP_GT_OQ>(p[1], margin[1]),
                       cmp<_CMP_GT_OQ>(p[2], margin[2])),
                   all(cmp<_CMP_LT_OQ>(p[0], below[0]), cmp<_CMP_LT_OQ>(p[1], below[1]),
                       cmp<_CMP_LT_OQ>(p[2], below[2])));
    };
    const __m256 separated = any(beyond(x), beyond(y));
    const __m256 undecided_edges = _mm256_andnot_ps(
        separated, any(uncertain(u, 2, 1), uncertain(v, 0, 2), uncertain(w, 1, 0)));
    const __m256 outside =
        any(separated,
            all(any(cmp<_CMP_LT_OQ>(u, zero), cmp<_CMP_LT_OQ>(v, zero), cmp<_CMP_LT_OQ>(w, zero)),
                any(cmp<_CMP_GT_OQ>(u, zero), cmp<_CMP_GT_OQ>(v, zero), cmp<_CMP_GT_OQ>(w, zero))));
    // Most lanes miss: skip the distance where no lane's line passes through its triangle.
    const unsigned edges = unsigned(_mm256_movemask_ps(undecided_edges));
    if ((valid & (edges | ~unsigned(_mm256_movemask_ps(outside)))) == 0) {
        out.accepted = out.scalar = 0;
        return;
    }
    // decide_distance
    const __m256 det = add(add(u, v), w);
    const __m256 inv_det = _mm256_div_ps(set(1.0f), det);
    const __m256 t = mul(add(add(mul(u, z[0]), mul(v, z[1])), mul(w, z[2])), inv_det);
    // ShearedTriangle::distance_error(t, |dir[kx]|, |dir[ky]|)
    const __m256 max_z = max(abs(z[0]), abs(z[1]), abs(z[2]));
    const __m256 max_x = max(abs(x[0]), abs(x[1]), abs(x[2]));
    const __m256 max_y = max(abs(y[0]), abs(y[1]), abs(y[2]));
    const __m256 spread = max(abs(sub(z[0], t)), abs(sub(z[1], t)), abs(sub(z[2], t)));
    const float gamma2 = rounding_gamma<float>(2), gamma3 = rounding_gamma<float>(3),
                gamma5 = rounding_gamma<float>(5);
    const __m256 delta_z = mul(set(gamma3), max_z);
    const __m256 delta_x = mul(set(gamma5), add(max_x, mul(s.shear_x, max_z)));
    const __m256 delta_y = mul(set(gamma5), add(max_y, mul(s.shear_y, max_z)));
    const __m256 delta_e = mul(
        set(2.0f),
        add(add(mul(mul(set(gamma2), max_x), max_y), mul(delta_y, max_x)), mul(delta_x, max_y)));
    const __m256 max_e = max(abs(u), abs(v), abs(w));
    const __m256 denominator =
        sub(sub(abs(det), mul(set(6.0f), delta_e)), mul(set(3.0f * gamma2), max_e));
    const __m256 numerator =
        mul(set(3.0f), add(add(add(add(mul(mul(set(gamma3), max_e), max_z), mul(delta_e, spread)),
                                   mul(delta_z, max_e)),
                               mul(delta_e, delta_z)),
                           mul(mul(set(gamma2), max_e), abs(t))));
    const __m256 bounded = all(cmp<_CMP_GT_OQ>(denominator, zero),
                               cmp<_CMP_GE_OQ>(mul(max_e, max_z), set(kSmallestDistanceProduct)));
    const __m256 error = _mm256_blendv_ps(
        set(kInfinity), add(_mm256_div_ps(numerator, denominator), mul(set(gamma2), abs(t))),
        bounded);
    const __m256 lo = tmin, hi = tmax;
    const __m256 near_end = add(t, error);
    const __m256 rejected = any(cmp<_CMP_LE_OQ>(near_end, zero), cmp<_CMP_LT_OQ>(near_end, lo),
                                cmp<_CMP_GT_OQ>(sub(t, error), hi));
    const __m256 trusted = all(cmp<_CMP_LE_OQ>(error, mul(t, set(kTrustedDistanceError))),
                               cmp<_CMP_LT_OQ>(t, set(kInfinity)));
    const __m256 in_range = all(cmp<_CMP_GE_OQ>(t, lo), cmp<_CMP_LE_OQ>(t, hi));
    // The line passes through the triangle and the distance was not rejected outright.
    const unsigned through = ~unsigned(_mm256_movemask_ps(any(outside, rejected))) & 0xffu;
    const unsigned trusted_lanes = unsigned(_mm256_movemask_ps(trusted));
    out.scalar = valid & (edges | (through & ~trusted_lanes));
    out.accepted =
        valid & ~edges & through & trusted_lanes & unsigned(_mm256_movemask_ps(in_range));
    if (out.accepted) {
        _mm256_store_ps(out.t, t);
        _mm256_store_ps(out.v, v);
        _mm256_store_ps(out.w, w);
        _mm256_store_ps(out.inv_det, inv_det);
    }
}

/// One ray against eight triangles: the triangles' corners in the ray's frame.
[[gnu::always_inline]] inline void intersect_triangle8(const WatertightRay& ray,
                                                       const TriangleBlock8& tris, unsigned valid,
                                                       float tmin, float tmax,
                                                       TriangleLanes8& out) {
    using namespace simd8;
    const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
    const __m256 sx = set(ray.sx), sy = set(ray.sy), sz = set(ray.sz);
    ShearedTriangles8 s;
    for (int c = 0; c < 3; ++c) {  // shear_triangle
        const __m256 rx = sub(_mm256_load_ps(tris.p[c][kx]), set(ray.org[kx]));
        const __m256 ry = sub(_mm256_load_ps(tris.p[c][ky]), set(ray.org[ky]));
        const __m256 rz = sub(_mm256_load_ps(tris.p[c][kz]), set(ray.org[kz]));
        s.x[c] = sub(rx, mul(sx, rz));
        s.y[c] = sub(ry, mul(sy, rz));
        s.z[c] = mul(sz, rz);
    }
    s.shear_x = set(std::abs(ray.dir[kx]));
    s.shear_y = set(std::abs(ray.dir[ky]));
    decide_triangles8(s, set(tmin), set(tmax), valid, out);
}

/// A triangle's corners as (x, y, z, 0) each: a lane picks its rays' axes with one permute.
struct TriangleCorners {
    alignas(16) float p[3][4];
};

inline TriangleCorners make_triangle_corners(const Triangle& tri) {
    const glm::vec3* p[3] = {&tri.p0, &tri.p1, &tri.p2};
    TriangleCorners corners;
    for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a) corners.p[c][a] = (*p[c])[a];
        corners.p[c][3] = 0.0f;  // never picked: the lanes' axes are 0, 1, 2
    }
    return corners;
}

/// make_watertight_ray for eight rays: each lane's axes kx, ky, kz (as permute indices), its
/// origin on those axes, its shear and |dir[kx]|, |dir[ky]|.
struct WatertightRays8 {
    __m256i k[3];
    __m256 org[3];
    __m256 sx, sy, sz;
    __m256 shear_x, shear_y;
};

inline WatertightRays8 make_watertight_rays8(const __m256 (&org)[3], const __m256 (&dir)[3]) {
    using namespace simd8;
    const __m256 ax = abs(dir[0]), ay = abs(dir[1]), az = abs(dir[2]);
    // kz = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2)
    const __m256 x_ge_y = cmp<_CMP_GE_OQ>(ax, ay);
    const __m256i z_is_0 = _mm256_castps_si256(all(x_ge_y, cmp<_CMP_GE_OQ>(ax, az)));
    const __m256i z_is_1 = _mm256_castps_si256(_mm256_andnot_ps(x_ge_y, cmp<_CMP_GE_OQ>(ay, az)));
    const auto pick = [&](int if_0, int if_1, int if_2) {
        return _mm256_blendv_epi8(
            _mm256_blendv_epi8(_mm256_set1_epi32(if_2), _mm256_set1_epi32(if_1), z_is_1),
            _mm256_set1_epi32(if_0), z_is_0);
    };
    const auto select = [&](const __m256(&v)[3], __m256i k) {
        const __m256 is_0 = _mm256_castsi256_ps(_mm256_cmpeq_epi32(k, _mm256_setzero_si256()));
        const __m256 is_1 = _mm256_castsi256_ps(_mm256_cmpeq_epi32(k, _mm256_set1_epi32(1)));
        return _mm256_blendv_ps(_mm256_blendv_ps(v[2], v[1], is_1), v[0], is_0);
    };
    WatertightRays8 r;
    r.k[2] = pick(0, 1, 2);
    const __m256 dir_z = select(dir, r.k[2]);
    // kx follows kz, ky follows kx; swapped for a negative dir[kz] to keep the winding.
    const __m256i kx = pick(1, 2, 0), ky = pick(2, 0, 1);
    const __m256i negative = _mm256_castps_si256(cmp<_CMP_LT_OQ>(dir_z, _mm256_setzero_ps()));
    r.k[0] = _mm256_blendv_epi8(kx, ky, negative);
    r.k[1] = _mm256_blendv_epi8(ky, kx, negative);
    const __m256 dir_x = select(dir, r.k[0]), dir_y = select(dir, r.k[1]);
    for (int a = 0; a < 3; ++a) r.org[a] = select(org, r.k[a]);
    r.sz = _mm256_div_ps(set(1.0f), dir_z);
    r.sx = mul(dir_x, r.sz);
    r.sy = mul(dir_y, r.sz);
    r.shear_x = abs(dir_x);
    r.shear_y = abs(dir_y);
    return r;
}

/// Eight rays against one triangle: the triangle's corners in each ray's frame.
[[gnu::always_inline]] inline void intersect_rays8(const WatertightRays8& rays,
                                                   const TriangleCorners& tri, __m256 tmin,
                                                   __m256 tmax, unsigned valid,
                                                   TriangleLanes8& out) {
    using namespace simd8;
    ShearedTriangles8 s;
    for (int c = 0; c < 3; ++c) {  // shear_triangle
        const __m256 corner = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(tri.p[c]));
        const __m256 rx = sub(_mm256_permutevar8x32_ps(corner, rays.k[0]), rays.org[0]);
        const __m256 ry = sub(_mm256_permutevar8x32_ps(corner, rays.k[1]), rays.org[1]);
        const __m256 rz = sub(_mm256_permutevar8x32_ps(corner, rays.k[2]), rays.org[2]);
        s.x[c] = sub(rx, mul(rays.sx, rz));
        s.y[c] = sub(ry, mul(rays.sy, rz));
        s.z[c] = mul(rays.sz, rz);
    }
    s.shear_x = rays.shear_x;
    s.shear_y = rays.shear_y;
    decide_triangles8(s, tmin, tmax, valid, out);
}

}  // namespace edacrt
