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
#include <utility>

#include "geometry/aabb.h"
#include "geometry/ray.h"

namespace edacrt {

/// A triangle's three corners, gathered once per frame from the indexed scene.
struct Triangle {
    glm::vec3 p0, p1, p2;
};

/// A ray prepared for the watertight test: the axis kz of the largest direction component
/// becomes the view axis, and the shear (sx, sy, sz) maps the direction to (0, 0, 1).
struct WatertightRay {
    glm::vec3 org;
    int kx, ky, kz;
    float sx, sy, sz;
    float shear_x, shear_y;  // |sx / sz|, |sy / sz|: the direction's kx, ky magnitudes
};

inline WatertightRay make_watertight_ray(const Ray& ray) {
    const glm::vec3 a = glm::abs(ray.dir);
    const int kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (ray.dir[kz] < 0.0f) std::swap(kx, ky);  // keep the winding, so U, V, W keep their sign
    const float sz = 1.0f / ray.dir[kz];
    return {ray.org,
            kx,
            ky,
            kz,
            ray.dir[kx] * sz,
            ray.dir[ky] * sz,
            sz,
            std::abs(ray.dir[kx]),
            std::abs(ray.dir[ky])};
}

/// Distance and barycentrics of a hit (u weights p1, v weights p2).
struct TriangleHit {
    float t, u, v;
};

/// The second half of the watertight test, from the scaled barycentrics (u, v, w) and the
/// sheared z of the corners: the inside test, the determinant and the distance.
template <typename Real>
inline bool finish_hit(Real u, Real v, Real w, Real az, Real bz, Real cz, float tmin, float tmax,
                       TriangleHit& out) {
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
    const Real det = u + v + w;
    if (det == 0) return false;
    const Real inv_det = Real(1) / det;
    const float t = float((u * az + v * bz + w * cz) * inv_det);
    if (!(t >= tmin && t <= tmax)) return false;
    out = {t, float(v * inv_det), float(w * inv_det)};
    return true;
}

/// gamma(n) = n u / (1 - n u), u = 2^-24: the relative bound of n rounded float operations.
constexpr float rounding_gamma(int n) {
    constexpr float u = 0x1p-24f;
    return float(n) * u / (1.0f - float(n) * u);
}

/// A bound on the rounding error of a hit's t, after pbrt-v3 (Pharr, Jakob, Humphreys, section
/// 3.9.6): a t at or below it may really be <= 0. From the sheared corners, the edge functions
/// and the shear (shear_x, shear_y = |dir_kx|, |dir_ky|): pbrt bounds the error of x - s_x z by
/// gamma(5)(max|x| + max|z|) assuming |s_x| <= 1; the s_x factor is kept here, so a far triangle
/// hit along an axis keeps its tight bound. Evaluated in Real, so the double path keeps its range
/// at tiny and huge coordinates.
template <typename Real>
inline Real hit_distance_error(Real ax, Real ay, Real az, Real bx, Real by, Real bz, Real cx,
                               Real cy, Real cz, Real u, Real v, Real w, Real shear_x,
                               Real shear_y) {
    const Real max_z = std::max({std::abs(az), std::abs(bz), std::abs(cz)});
    const Real max_x = std::max({std::abs(ax), std::abs(bx), std::abs(cx)});
    const Real max_y = std::max({std::abs(ay), std::abs(by), std::abs(cy)});
    const Real gamma2 = rounding_gamma(2), gamma3 = rounding_gamma(3), gamma5 = rounding_gamma(5);
    const Real delta_z = gamma3 * max_z;
    const Real delta_x = gamma5 * (max_x + shear_x * max_z);
    const Real delta_y = gamma5 * (max_y + shear_y * max_z);
    const Real delta_e = 2 * (gamma2 * max_x * max_y + delta_y * max_x + delta_x * max_y);
    const Real max_e = std::max({std::abs(u), std::abs(v), std::abs(w)});
    return 3 * (gamma3 * max_e * max_z + delta_e * max_z + delta_z * max_e) / std::abs(u + v + w);
}

/// The rare half of intersect_triangle (exact zeros, extreme magnitudes), out of line so the
/// common path stays small enough to inline into the traversal loops.
[[gnu::noinline]] inline bool finish_hit_in_double(const WatertightRay& r, float ax, float ay,
                                                   float az, float bx, float by, float bz, float cx,
                                                   float cy, float cz, float tmin, float tmax,
                                                   TriangleHit& out) {
    const double ud = double(cx) * double(by) - double(cy) * double(bx);
    const double vd = double(ax) * double(cy) - double(ay) * double(cx);
    const double wd = double(bx) * double(ay) - double(by) * double(ax);
    if (!finish_hit(ud, vd, wd, double(az), double(bz), double(cz), tmin, tmax, out)) return false;
    return double(out.t) > hit_distance_error<double>(ax, ay, az, bx, by, bz, cx, cy, cz, ud, vd,
                                                      wd, r.shear_x, r.shear_y);
}

/// Intersects the ray with the triangle. Returns true for a hit with tmin <= t <= tmax whose t
/// is also conservatively positive (beyond its rounding error bound, as in pbrt), so a ray
/// spawned from a surface (geometry/offset.h) cannot hit that surface again.
/// Both faces are hit; a degenerate (zero-area as seen from the ray) triangle is never hit.
[[gnu::always_inline]] inline bool intersect_triangle(const WatertightRay& r, const Triangle& tri,
                                                      float tmin, float tmax, TriangleHit& out) {
    const glm::vec3 A = tri.p0 - r.org;
    const glm::vec3 B = tri.p1 - r.org;
    const glm::vec3 C = tri.p2 - r.org;

    const float ax = A[r.kx] - r.sx * A[r.kz];
    const float ay = A[r.ky] - r.sy * A[r.kz];
    const float bx = B[r.kx] - r.sx * B[r.kz];
    const float by = B[r.ky] - r.sy * B[r.kz];
    const float cx = C[r.kx] - r.sx * C[r.kz];
    const float cy = C[r.ky] - r.sy * C[r.kz];

    const float u = cx * by - cy * bx;
    const float v = ax * cy - ay * cx;
    const float w = bx * ay - by * ax;
    const float az = r.sz * A[r.kz];
    const float bz = r.sz * B[r.kz];
    const float cz = r.sz * C[r.kz];
    // An exact zero may be rounding; a tiny determinant (coordinates below ~1e-9) leaves the
    // products denormal and a huge one (above ~1e8) overflows them. Decide those in double,
    // where the products of floats are exact and the range is ample.
    constexpr float kSmallestSafeDeterminant = 1e-18f, kLargestSafeDeterminant = 1e16f;
    const float det = std::abs(u + v + w);
    if (u == 0.0f || v == 0.0f || w == 0.0f ||
        !(det >= kSmallestSafeDeterminant && det <= kLargestSafeDeterminant)) [[unlikely]]
        return finish_hit_in_double(r, ax, ay, az, bx, by, bz, cx, cy, cz, tmin, tmax, out);
    if (!finish_hit(u, v, w, az, bz, cz, tmin, tmax, out)) return false;
    return out.t >
           hit_distance_error(ax, ay, az, bx, by, bz, cx, cy, cz, u, v, w, r.shear_x, r.shear_y);
}

/// The triangle's box, widened by 2^-20 of its largest coordinate magnitude. The watertight
/// test rounds at the scale of the coordinates, so it may accept a ray that passes a few ulps
/// outside the exact triangle (or a hit at t = -0 from an origin on the surface); a divide-and-
/// conquer filter or a BVH that culls with these boxes never rejects such a ray.
inline Aabb conservative_bounds(const Triangle& tri) {
    Aabb box;
    box.extend(tri.p0);
    box.extend(tri.p1);
    box.extend(tri.p2);
    const glm::vec3 magnitude = glm::max(glm::abs(box.lo), glm::abs(box.hi));
    const float pad = std::max({magnitude.x, magnitude.y, magnitude.z}) * 0x1p-20f;
    box.lo -= glm::vec3(pad);
    box.hi += glm::vec3(pad);
    return box;
}

inline glm::vec3 centroid(const Triangle& tri) {
    return (tri.p0 + tri.p1 + tri.p2) * (1.0f / 3.0f);
}

/// The unnormalised geometric normal, oriented by the winding p0 -> p1 -> p2.
inline glm::vec3 geometric_normal(const Triangle& tri) {
    return glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
}

}  // namespace edacrt
