#include "geometry/triangle.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace edacrt {
namespace {

/// The unnormalised normal in double. The corners are floats, so their differences are exact
/// in double, the products of two differences are exact, and each component is rounded once:
/// a sliver's plane keeps its orientation.
glm::dvec3 normal_in_double(const Triangle& tri) {
    const glm::dvec3 p0(tri.p0);
    return glm::cross(glm::dvec3(tri.p1) - p0, glm::dvec3(tri.p2) - p0);
}

/// The distance half of refine_hit_in_double: the plane's t in double, or false when the ray
/// is parallel to the plane, t is outside [tmin, tmax], not finite as a float or within its
/// rounding error of the origin, or off the triangle's box.
bool refine_distance(const WatertightRay& r, const Triangle& tri, float tmin, float tmax,
                     double& t_out) {
    // t from the plane, t = n.(p0 - o) / n.d, with n exact to one rounding (normal_in_double).
    // (Weighting the sheared z by the barycentrics instead cancels twice for a long triangle
    // hit close to its middle: 1e-4 relative in double for a 1:1e6 sliver.)
    const glm::dvec3 n = normal_in_double(tri);
    const glm::dvec3 a = glm::dvec3(tri.p0) - glm::dvec3(r.org), d(r.dir);
    const double den = glm::dot(n, d);
    if (den == 0.0) return false;  // parallel to the plane
    const double t = glm::dot(n, a) / den;
    // Each product and sum rounds once (n already once): the numerator is within gamma(4) of
    // sum |n_i a_i|, the denominator within gamma(3) of sum |n_i d_i|; gamma(6) covers both and
    // the inexact differences of corners far apart in magnitude.
    const glm::dvec3 na = glm::abs(n * a), nd = glm::abs(n * d);
    const double error = rounding_gamma<double>(6) *
                             (na.x + na.y + na.z + std::abs(t) * (nd.x + nd.y + nd.z)) /
                             std::abs(den) +
                         rounding_gamma<double>(2) * std::abs(t);
    // Against tmin and tmax in double: the float t may round onto them.
    const float t_float = float(t);
    if (!(t >= double(tmin) && t <= double(tmax) && t_float < kInfinity && t > error)) return false;
    // The double path is exact only to its own rounding: corners and an origin too far apart
    // in magnitude (beyond 2^29) have inexact differences, and an origin 2^53 away rounds the
    // double shear (6.75 + 1.5e16), so the inside test may pass anywhere on the plane (found by
    // the fuzzer: a 1:1e29 triangle, an origin at 1e28; a unit triangle hit at y = -1.5e16 from
    // 2^53 away). A hit must at least lie in the triangle's box, up to its error.
    const glm::dvec3 point = glm::dvec3(r.org) + t * d;
    const glm::dvec3 lo =
        glm::min(glm::dvec3(tri.p0), glm::min(glm::dvec3(tri.p1), glm::dvec3(tri.p2)));
    const glm::dvec3 hi =
        glm::max(glm::dvec3(tri.p0), glm::max(glm::dvec3(tri.p1), glm::dvec3(tri.p2)));
    // Per axis: the distance's error, and the float inside test's resolution (2^-20 of the
    // coordinates), by which a ray may be given a triangle it passes just beside.
    const glm::dvec3 o(r.org);
    const glm::dvec3 reach =
        error * glm::abs(d) + 0x1p-20 * glm::max(glm::abs(o), glm::max(glm::abs(lo), glm::abs(hi)));
    if (glm::any(glm::lessThan(point, lo - reach)) || glm::any(glm::greaterThan(point, hi + reach)))
        return false;
    t_out = t;
    return true;
}

/// The hit at distance t with the barycentrics of the pair sheared in double; false when the
/// triangle is seen edge-on.
bool sheared_hit(const ShearedTriangle<double>& s, double t, TriangleHit& out) {
    const double det = s.u + s.v + s.w;
    if (det == 0.0) return false;
    out = {float(t), float(s.v / det), float(s.w / det)};
    return true;
}

}  // namespace

ShearedTriangle<double> shear_triangle_in_double(const WatertightRay& r, const Triangle& tri) {
    const glm::dvec3 org(r.org);
    const glm::dvec3 A = glm::dvec3(tri.p0) - org;
    const glm::dvec3 B = glm::dvec3(tri.p1) - org;
    const glm::dvec3 C = glm::dvec3(tri.p2) - org;
    const double sz = 1.0 / double(r.dir[r.kz]);
    const double sx = double(r.dir[r.kx]) * sz, sy = double(r.dir[r.ky]) * sz;
    ShearedTriangle<double> s;
    s.ax = A[r.kx] - sx * A[r.kz];
    s.ay = A[r.ky] - sy * A[r.kz];
    s.bx = B[r.kx] - sx * B[r.kz];
    s.by = B[r.ky] - sy * B[r.kz];
    s.cx = C[r.kx] - sx * C[r.kz];
    s.cy = C[r.ky] - sy * C[r.kz];
    s.u = s.cx * s.by - s.cy * s.bx;
    s.v = s.ax * s.cy - s.ay * s.cx;
    s.w = s.bx * s.ay - s.by * s.ax;
    s.az = sz * A[r.kz];
    s.bz = sz * B[r.kz];
    s.cz = sz * C[r.kz];
    return s;
}

bool refine_hit_in_double(const WatertightRay& r, const Triangle& tri, float tmin, float tmax,
                          TriangleHit& out) {
    // Most candidates that come here are rejected by their distance: shear only for a hit.
    double t;
    return refine_distance(r, tri, tmin, tmax, t) &&
           sheared_hit(shear_triangle_in_double(r, tri), t, out);
}

bool intersect_triangle_rare(const WatertightRay& r, const Triangle& tri,
                             const ShearedTriangle<float>& f, float tmin, float tmax,
                             TriangleHit& out) {
    const TriangleErrors e = corner_errors(r, f);
    if (separated_from_ray(f, e)) return false;
    const ShearedTriangle<double> d = shear_triangle_in_double(r, tri);
    const double u = edge_uncertain(f.u, e.c, e.b) ? d.u : double(f.u);
    const double v = edge_uncertain(f.v, e.a, e.c) ? d.v : double(f.v);
    const double w = edge_uncertain(f.w, e.b, e.a) ? d.w : double(f.w);
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
    if (u + v + w == 0) return false;
    double t;
    return refine_distance(r, tri, tmin, tmax, t) && sheared_hit(d, t, out);
}

glm::vec3 unit_normal(const Triangle& tri) {
    const glm::dvec3 n = normal_in_double(tri);
    const double length = glm::length(n);
    return length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.0f);
}

double triangle_area(const Triangle& tri) { return 0.5 * glm::length(normal_in_double(tri)); }

bool is_degenerate(const Triangle& tri) {
    const glm::dvec3 ab = glm::dvec3(tri.p1) - glm::dvec3(tri.p0);
    const glm::dvec3 ac = glm::dvec3(tri.p2) - glm::dvec3(tri.p0);
    return glm::cross(ab, ac) == glm::dvec3(0.0);
}

}  // namespace edacrt
