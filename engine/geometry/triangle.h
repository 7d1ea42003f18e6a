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
};

inline WatertightRay make_watertight_ray(const Ray& ray) {
    const glm::vec3 a = glm::abs(ray.dir);
    const int kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (ray.dir[kz] < 0.0f) std::swap(kx, ky);  // keep the winding, so U, V, W keep their sign
    const float sz = 1.0f / ray.dir[kz];
    return {ray.org, kx, ky, kz, ray.dir[kx] * sz, ray.dir[ky] * sz, sz};
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

/// Intersects the ray with the triangle. Returns true for a hit with tmin <= t <= tmax.
/// Both faces are hit; a degenerate (zero-area as seen from the ray) triangle is never hit.
inline bool intersect_triangle(const WatertightRay& r, const Triangle& tri, float tmin, float tmax,
                               TriangleHit& out) {
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
        !(det >= kSmallestSafeDeterminant && det <= kLargestSafeDeterminant)) {
        const double ud = double(cx) * double(by) - double(cy) * double(bx);
        const double vd = double(ax) * double(cy) - double(ay) * double(cx);
        const double wd = double(bx) * double(ay) - double(by) * double(ax);
        return finish_hit(ud, vd, wd, double(az), double(bz), double(cz), tmin, tmax, out);
    }
    return finish_hit(u, v, w, az, bz, cz, tmin, tmax, out);
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
