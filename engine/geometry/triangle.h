#pragma once
// Watertight ray/triangle intersection (Woop, Benthin, Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2013). A ray through a shared edge or vertex of a closed mesh cannot pass
// between the triangles: the edge functions of a shared edge are computed from the same two
// sheared vertices and are exact negatives of each other, and exact zeros are recomputed in
// double precision. This needs -ffp-contract=off (see CMakeLists.txt).
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <utility>

#include "geometry/aabb.h"
#include "geometry/ray.h"

namespace edacrt {

/// A triangle's three corners, gathered once per frame from the indexed scene.
struct Triangle {
    glm::vec3 p0, p1, p2;
};

/// A ray prepared for the watertight test: the axis kz of the largest direction component
/// becomes the view axis, and the shear (sx, sy, sz) maps the direction to (0, 0, 1). The
/// direction is kept for the double-precision refinement and the error bound.
struct WatertightRay {
    glm::vec3 org;
    glm::vec3 dir;
    int kx, ky, kz;
    float sx, sy, sz;
    float shear;  // |dir[kx]| + |dir[ky]|, for the sheared corners' error (corner_error)
};

inline WatertightRay make_watertight_ray(const Ray& ray) {
    const glm::vec3 a = glm::abs(ray.dir);
    const int kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (ray.dir[kz] < 0.0f) std::swap(kx, ky);  // keep the winding, so U, V, W keep their sign
    const float sz = 1.0f / ray.dir[kz];
    return {ray.org,
            ray.dir,
            kx,
            ky,
            kz,
            ray.dir[kx] * sz,
            ray.dir[ky] * sz,
            sz,
            std::abs(ray.dir[kx]) + std::abs(ray.dir[ky])};
}

/// Distance and barycentrics of a hit (u weights p1, v weights p2).
struct TriangleHit {
    float t, u, v;
};

/// gamma(n) = n u / (1 - n u): the relative bound of n rounded operations of unit roundoff u
/// (2^-24 for float, 2^-53 for double).
template <typename Real>
constexpr Real rounding_gamma(int n) {
    constexpr Real u = std::numeric_limits<Real>::epsilon() / 2;
    return Real(n) * u / (1 - Real(n) * u);
}

/// Below this, the products of t's numerator (edge function times sheared z) may be denormal
/// and lose digits; t is then computed in double. The bound's dominant term, gamma(3) times
/// this, stays far above the denormals' absolute error of 2^-149 per operation.
inline constexpr float kSmallestDistanceProduct = 0x1p-100f;

/// The sheared corners (x, y, z of A, B, C relative to the ray origin, in the ray's frame) and
/// the scaled barycentrics U, V, W of one ray/triangle pair, in float or double.
template <typename Real>
struct ShearedTriangle {
    Real ax, ay, az, bx, by, bz, cx, cy, cz;
    Real u, v, w;

    /// A bound on the rounding error of t = (u az + v bz + w cz) / (u + v + w) for corners
    /// computed in float, after pbrt-v3 (Pharr, Jakob, Humphreys, section 3.9.6) with a tighter
    /// middle term. pbrt bounds the sheared corners' errors, dx = gamma(5)(max|x| + |s_x| max|z|)
    /// (the |s_x| = |dir_kx| factor kept, so an axis-aligned ray keeps a tight bound), dz =
    /// gamma(3) max|z|, and from them the edge functions' error de. Perturbing t = N / E by
    /// errors dN, dE gives t' - t = (dN - t dE) / (E + dE), and dN - t dE = sum de_i (z_i - t)
    /// + sum e_i dz_i + rounding: the edge function errors weigh the corners' spread in z about
    /// t, not max|z| as in pbrt. For a small triangle far away that spread is its size, not its
    /// distance, so the bound stays near 1e-7 t instead of 1e-4 t. For a long thin triangle seen
    /// from close by the spread is its length and the bound large: intersect_triangle then
    /// refines in double. Infinite when E may be within rounding of zero, or when the products
    /// e_i z_i may be denormal (below kSmallestDistanceProduct: a direction of 1e33 makes z
    /// near 1e-33, and t lost a third of its value to the products' missing digits).
    Real distance_error(Real t, Real shear_x, Real shear_y) const {
        const Real max_z = std::max({std::abs(az), std::abs(bz), std::abs(cz)});
        const Real max_x = std::max({std::abs(ax), std::abs(bx), std::abs(cx)});
        const Real max_y = std::max({std::abs(ay), std::abs(by), std::abs(cy)});
        const Real max_e = std::max({std::abs(u), std::abs(v), std::abs(w)});
        if (!(max_e * max_z >= Real(kSmallestDistanceProduct)))
            return std::numeric_limits<Real>::infinity();
        const Real spread = std::max({std::abs(az - t), std::abs(bz - t), std::abs(cz - t)});
        const Real gamma2 = rounding_gamma<float>(2), gamma3 = rounding_gamma<float>(3),
                   gamma5 = rounding_gamma<float>(5);
        const Real delta_z = gamma3 * max_z;
        const Real delta_x = gamma5 * (max_x + shear_x * max_z);
        const Real delta_y = gamma5 * (max_y + shear_y * max_z);
        const Real delta_e = 2 * (gamma2 * max_x * max_y + delta_y * max_x + delta_x * max_y);
        // |dE| <= 3 de + the rounding of the sum; the spread about the computed t may be off by
        // the error itself, which takes another 3 de from the denominator.
        const Real denominator = std::abs(u + v + w) - 6 * delta_e - 3 * gamma2 * max_e;
        if (!(denominator > 0)) return std::numeric_limits<Real>::infinity();
        const Real numerator = 3 * (gamma3 * max_e * max_z + delta_e * spread + delta_z * max_e +
                                    delta_e * delta_z + gamma2 * max_e * std::abs(t));
        return numerator / denominator + gamma2 * std::abs(t);
    }
};

/// The ray/triangle pair in the ray's frame, in float (the watertight test's own arithmetic).
[[gnu::always_inline]] inline ShearedTriangle<float> shear_triangle(const WatertightRay& r,
                                                                    const Triangle& tri) {
    const glm::vec3 A = tri.p0 - r.org;
    const glm::vec3 B = tri.p1 - r.org;
    const glm::vec3 C = tri.p2 - r.org;
    ShearedTriangle<float> s;
    s.ax = A[r.kx] - r.sx * A[r.kz];
    s.ay = A[r.ky] - r.sy * A[r.kz];
    s.bx = B[r.kx] - r.sx * B[r.kz];
    s.by = B[r.ky] - r.sy * B[r.kz];
    s.cx = C[r.kx] - r.sx * C[r.kz];
    s.cy = C[r.ky] - r.sy * C[r.kz];
    s.u = s.cx * s.by - s.cy * s.bx;
    s.v = s.ax * s.cy - s.ay * s.cx;
    s.w = s.bx * s.ay - s.by * s.ax;
    s.az = r.sz * A[r.kz];
    s.bz = r.sz * B[r.kz];
    s.cz = r.sz * C[r.kz];
    return s;
}

/// The same pair in double, from the float inputs themselves (origin, direction, corners): no
/// float rounding of the shear, so the edge functions of a sliver keep their significant
/// digits where the float ones cancel (products near 3e4 whose difference is near 5).
ShearedTriangle<double> shear_triangle_in_double(const WatertightRay& r, const Triangle& tri);

/// The rounding error of one sheared corner (x, y, z) of shear_triangle, for edge_uncertain:
/// `error` bounds |dx| and |dy|, `size` is |x| + |y| + error. The corner is a difference from
/// the origin, sheared: x = (P_kx - o_kx) - s_x (P_kz - o_kz), so it carries the roundings of
/// the translation and the shear, relative to |P - o| and not to |x|: for an origin 1e6 away
/// that is 0.06, more than a unit triangle's sheared size. With |s_x (P_kz - o_kz)| <=
/// |dir_kx| |z| (1 + 3u), |dx| <= gamma(4) (|x| + |dir_kx| |z|), and likewise for y; the
/// bound takes 2^-20 (four times gamma(4), for the roundings of the edge function's products
/// and of the bound itself) of |x| + |y| + (|dir_kx| + |dir_ky|) |z|.
struct CornerError {
    float error, size;
};

[[gnu::always_inline]] inline CornerError corner_error(float x, float y, float z, float shear) {
    constexpr float kCornerRounding = 0x1p-20f;
    const float xy = std::abs(x) + std::abs(y);
    const float error = kCornerRounding * (xy + shear * std::abs(z));
    return {error, xy + error};
}

/// Whether the float edge function e = x_p y_q - y_p x_q of corners p, q may have another
/// sign than that of the exact triangle: |e| within e's error bound, de <= dp (n_q + dq) +
/// dq (n_p + dp) (n = |x| + |y|, d = corner_error's error; it covers the products' rounding,
/// as d >= 2^-20 n), or below 2^-100 (denormal products lose digits), or not finite. A sign
/// beyond the bound is the exact one, so an edge decided in float and one recomputed in double
/// describe the same triangle. The bound depends only on the edge's two corners, and the
/// triangle across the edge computes -e from the same corners, so both triangles decide alike
/// whether to recompute the edge in double: the test stays watertight.
[[gnu::always_inline]] inline bool edge_uncertain(float e, const CornerError& p,
                                                  const CornerError& q) {
    constexpr float kTiny = 0x1p-100f;
    const float magnitude = std::abs(e);
    return !(magnitude > std::max(p.error * q.size + q.error * p.size, kTiny)) ||
           !(magnitude < kInfinity);
}

/// The corner errors of a sheared triangle's corners A, B, C, in that order.
struct TriangleErrors {
    CornerError a, b, c;
};

/// Whether all three sheared corners lie beyond twice their rounding error on one side of
/// x = 0 or of y = 0: the exact triangle then lies in that open half-plane, away from the ray's
/// line at the origin, so the ray misses it whatever the float edge functions say. Small
/// triangles far from the origin have edge functions below their error bound (edge_uncertain:
/// the bound scales with the corners' distance from the ray, not with the triangle), and this
/// decides them without the double-precision path, which would find the same miss: its corners
/// are accurate to far less than the margin (Conference's diffuse rays: 40 such triangles per
/// ray, which made that path a third of the trace). It looks at one triangle's corners only, so
/// the test stays watertight: the ray's line is at least the margin away from every edge.
template <class Corners>
[[gnu::always_inline]] inline bool separated_from_ray(const Corners& s, const TriangleErrors& d) {
    const auto beyond = [](float p, float q, float r, float ep, float eq, float er) {
        return (p > 2.0f * ep && q > 2.0f * eq && r > 2.0f * er) ||
               (p < -2.0f * ep && q < -2.0f * eq && r < -2.0f * er);
    };
    return beyond(s.ax, s.bx, s.cx, d.a.error, d.b.error, d.c.error) ||
           beyond(s.ay, s.by, s.cy, d.a.error, d.b.error, d.c.error);
}

[[gnu::always_inline]] inline TriangleErrors corner_errors(const WatertightRay& r,
                                                           const ShearedTriangle<float>& s) {
    return {corner_error(s.ax, s.ay, s.az, r.shear), corner_error(s.bx, s.by, s.bz, r.shear),
            corner_error(s.cx, s.cy, s.cz, r.shear)};
}

/// A hit's distance is decided in float when its error bound is below this fraction of t
/// (so float distances are within 2^-17 = 7.6e-6 relative); otherwise it is recomputed in
/// double. Measured: the double path runs for under 1% of the candidates on camera rays.
inline constexpr float kTrustedDistanceError = 0x1p-17f;

/// The distance, barycentrics and acceptance of a triangle the ray's line passes through,
/// computed in double from the inputs (see shear_triangle_in_double): accepts a t in
/// [tmin, tmax], finite as a float and beyond its (double) rounding error bound. The edge
/// functions sheared in double have the signs the inside test decided by (edge_uncertain), so
/// the barycentrics lie in the triangle.
bool refine_hit_in_double(const WatertightRay& r, const Triangle& tri, float tmin, float tmax,
                          TriangleHit& out);

/// The inside test when some edge function is uncertain in float (edge_uncertain: within its
/// error bound, denormal or overflowing): those edges are recomputed in double from the inputs
/// (an exact zero there still counts as on the edge, as in Woop et al.), the others keep their
/// float sign, which is exact, so all three describe one triangle (before edge_uncertain
/// counted the corners' rounding, a far ray's float signs described another one, and rays 60
/// units beside a unit triangle 1e6 away were accepted); the distance and barycentrics are
/// then computed in double. Out of line so the common path
/// stays small enough to inline into the traversal loops.
bool intersect_triangle_rare(const WatertightRay& r, const Triangle& tri,
                             const ShearedTriangle<float>& s, float tmin, float tmax,
                             TriangleHit& out);

/// The distance half of the ray/triangle test, once the ray's line is known to pass through the
/// triangle: decided in float when the error bound is small against t, otherwise recomputed in
/// double (long thin triangles, rays starting close to a large triangle), so slivers are
/// neither rejected for a large bound nor given a wrong t. Accepts a t in [tmin, tmax], finite,
/// and conservatively positive (beyond its rounding error bound, as in pbrt), so a ray spawned
/// from a surface (geometry/offset.h) cannot hit that surface again.
[[gnu::always_inline]] inline bool decide_distance(const WatertightRay& r, const Triangle& tri,
                                                   const ShearedTriangle<float>& s, float det,
                                                   float tmin, float tmax, TriangleHit& out) {
    const float inv_det = 1.0f / det;
    const float t = (s.u * s.az + s.v * s.bz + s.w * s.cz) * inv_det;
    const float error = s.distance_error(t, std::abs(r.dir[r.kx]), std::abs(r.dir[r.ky]));
    // Surely behind the origin, before tmin or after tmax. (Written so that a NaN from
    // overflowing corners falls through to the double path.)
    if (t + error <= 0.0f || t + error < tmin || t - error > tmax) return false;
    // Accurate: decided in float. Which path computes t depends only on the ray and the
    // triangle, never on [tmin, tmax], so a triangle reports the same t in every traversal.
    if (error <= t * kTrustedDistanceError && t < kInfinity) [[likely]] {
        if (!(t >= tmin && t <= tmax)) return false;
        out = {t, s.v * inv_det, s.w * inv_det};
        return true;
    }
    return refine_hit_in_double(r, tri, tmin, tmax, out);
}

/// Products below ~1e-9 coordinates go denormal and above ~1e8 overflow: decided in double.
[[gnu::always_inline]] inline bool safe_determinant(float det) {
    constexpr float kSmallestSafeDeterminant = 1e-18f, kLargestSafeDeterminant = 1e16f;
    return std::abs(det) >= kSmallestSafeDeterminant && std::abs(det) <= kLargestSafeDeterminant;
}

/// Intersects the ray with the triangle: Woop's float inside test, with every edge function
/// whose sign float cannot decide (edge_uncertain) recomputed in double, then decide_distance.
/// Returns true for a hit with tmin <= t <= tmax, t finite and conservatively positive. Both
/// faces are hit; a degenerate (zero-area as seen from the ray) triangle is never hit.
[[gnu::always_inline]] inline bool intersect_triangle(const WatertightRay& r, const Triangle& tri,
                                                      float tmin, float tmax, TriangleHit& out) {
    const ShearedTriangle<float> s = shear_triangle(r, tri);
    const TriangleErrors d = corner_errors(r, s);
    // One branch for the three edges (bitwise: rarely true, so not worth short-circuiting).
    if (int(edge_uncertain(s.u, d.c, d.b)) | int(edge_uncertain(s.v, d.a, d.c)) |
        int(edge_uncertain(s.w, d.b, d.a))) [[unlikely]]
        return intersect_triangle_rare(r, tri, s, tmin, tmax, out);
    if ((s.u < 0.0f || s.v < 0.0f || s.w < 0.0f) && (s.u > 0.0f || s.v > 0.0f || s.w > 0.0f))
        return false;
    return decide_distance(r, tri, s, s.u + s.v + s.w, tmin, tmax, out);
}

/// The box of the triangle's corners.
inline Aabb corners_bounds(const Triangle& tri) {
    return {glm::min(glm::min(tri.p0, tri.p1), tri.p2), glm::max(glm::max(tri.p0, tri.p1), tri.p2)};
}

/// What conservative_bounds adds on every side of the box of a triangle's corners: 2^-20 of
/// its largest coordinate magnitude.
inline float conservative_padding(const Aabb& corners) {
    const glm::vec3 magnitude = glm::max(glm::abs(corners.lo), glm::abs(corners.hi));
    return std::max({magnitude.x, magnitude.y, magnitude.z}) * 0x1p-20f;
}

/// The box of a triangle's corners, widened by conservative_padding() (see
/// conservative_bounds(const Triangle&)).
inline Aabb conservative_bounds(Aabb box) {
    const float pad = conservative_padding(box);
    box.lo -= glm::vec3(pad);
    box.hi += glm::vec3(pad);
    return box;
}

/// The triangle's box, widened by 2^-20 of its largest coordinate magnitude. The watertight
/// test rounds at the scale of the coordinates, so it may accept a ray that passes a few ulps
/// outside the exact triangle (or a hit at t = -0 from an origin on the surface); a divide-and-
/// conquer filter or a BVH that culls with these boxes never rejects such a ray.
inline Aabb conservative_bounds(const Triangle& tri) {
    return conservative_bounds(corners_bounds(tri));
}

/// Each corner scaled before the sum, so corners near the float range cannot overflow it.
inline glm::vec3 centroid(const Triangle& tri) {
    constexpr float kThird = 1.0f / 3.0f;
    return tri.p0 * kThird + tri.p1 * kThird + tri.p2 * kThird;
}

/// The unit geometric normal, oriented by the winding p0 -> p1 -> p2; zero for a degenerate
/// triangle. In double: the float cross product of two nearly parallel long edges (a sliver)
/// is off by up to 1e-3 rad, enough to offset a spawned ray to the wrong side.
glm::vec3 unit_normal(const Triangle& tri);

/// The triangle's area, in double for the same reason.
double triangle_area(const Triangle& tri);

/// Exactly zero area, computed in double; this also catches two coincident corners. Such
/// triangles are kept (they keep their number) and never hit.
bool is_degenerate(const Triangle& tri);

/// Two corners at the same point: intersect_triangle never hits such a triangle, so tracers may
/// leave it out of their work. With A = B (the others alike) the sheared corners are equal, so
/// W = B x A = bx ay - by ax is exactly 0 and V = A x C is exactly -U (products commute, a - b
/// is exactly -(b - a), and no FMA contracts them: -ffp-contract=off), in float and in double:
/// either U and V have opposite signs, or u + v + w = 0; both reject. (Conference has 52,670
/// of them in 331,179 triangles; each went to the double-precision path, its edge W being 0.)
inline bool has_coincident_corners(const Triangle& tri) {
    return tri.p0 == tri.p1 || tri.p1 == tri.p2 || tri.p2 == tri.p0;
}

}  // namespace edacrt
