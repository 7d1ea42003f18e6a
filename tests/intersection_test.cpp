// Ray/triangle and ray/box kernels: hand-computed cases, the numerically hard ones, and a
// comparison with a double-precision reference on random rays.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/ray_box.h"
#include "geometry/triangle.h"

namespace edacrt {
namespace {

constexpr Triangle kUnitTriangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

bool hit_triangle(const Ray& ray, const Triangle& tri, TriangleHit& out) {
    return intersect_triangle(make_watertight_ray(ray), tri, ray.tmin, ray.tmax, out);
}

TEST(TriangleIntersection, HandComputedHit) {
    const Ray ray{{0.25f, 0.5f, 2.0f}, {0, 0, -1}};
    TriangleHit hit;
    ASSERT_TRUE(hit_triangle(ray, kUnitTriangle, hit));
    EXPECT_FLOAT_EQ(hit.t, 2.0f);
    EXPECT_FLOAT_EQ(hit.u, 0.25f);  // weight of p1 = (1,0,0)
    EXPECT_FLOAT_EQ(hit.v, 0.5f);   // weight of p2 = (0,1,0)
}

TEST(TriangleIntersection, BothFacesAreHit) {
    const Ray ray{{0.2f, 0.2f, -3.0f}, {0, 0, 1}};
    TriangleHit hit;
    ASSERT_TRUE(hit_triangle(ray, kUnitTriangle, hit));
    EXPECT_FLOAT_EQ(hit.t, 3.0f);
}

TEST(TriangleIntersection, ObliqueRay) {
    // From (1,1,1) towards (0.2, 0.3, 0): direction (-0.8, -0.7, -1), t = 1.
    const Ray ray{{1, 1, 1}, {-0.8f, -0.7f, -1.0f}};
    TriangleHit hit;
    ASSERT_TRUE(hit_triangle(ray, kUnitTriangle, hit));
    EXPECT_NEAR(hit.t, 1.0f, 1e-6f);
    EXPECT_NEAR(hit.u, 0.2f, 1e-6f);
    EXPECT_NEAR(hit.v, 0.3f, 1e-6f);
}

TEST(TriangleIntersection, Misses) {
    TriangleHit hit;
    EXPECT_FALSE(hit_triangle({{0.6f, 0.6f, 1}, {0, 0, -1}}, kUnitTriangle, hit));  // outside
    EXPECT_FALSE(hit_triangle({{0.2f, 0.2f, 1}, {0, 0, 1}}, kUnitTriangle, hit));   // behind
    EXPECT_FALSE(hit_triangle({{0.2f, 0.2f, 1}, {1, 0, 0}}, kUnitTriangle, hit));   // parallel
}

TEST(TriangleIntersection, RespectsTminAndTmax) {
    TriangleHit hit;
    EXPECT_FALSE(hit_triangle({{0.2f, 0.2f, 2}, {0, 0, -1}, 0.0f, 1.5f}, kUnitTriangle, hit));
    EXPECT_FALSE(hit_triangle({{0.2f, 0.2f, 2}, {0, 0, -1}, 2.5f, kInfinity}, kUnitTriangle, hit));
    EXPECT_TRUE(hit_triangle({{0.2f, 0.2f, 2}, {0, 0, -1}, 2.0f, 2.0f}, kUnitTriangle, hit));
}

TEST(TriangleIntersection, DegenerateTrianglesAreNeverHit) {
    TriangleHit hit;
    const Triangle point{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const Triangle line{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}};
    EXPECT_FALSE(hit_triangle({{0, 0, 1}, {0, 0, -1}}, point, hit));
    EXPECT_FALSE(hit_triangle({{1, 1, 1}, {0, 0, -1}}, line, hit));
}

TEST(TriangleIntersection, EdgeAndVertexHits) {
    TriangleHit hit;
    EXPECT_TRUE(hit_triangle({{0.5f, 0.0f, 1}, {0, 0, -1}}, kUnitTriangle, hit));  // on an edge
    EXPECT_TRUE(hit_triangle({{0.0f, 0.0f, 1}, {0, 0, -1}}, kUnitTriangle, hit));  // on a vertex
    EXPECT_TRUE(hit_triangle({{0.5f, 0.5f, 1}, {0, 0, -1}}, kUnitTriangle, hit));  // hypotenuse
}

TEST(TriangleIntersection, HugeAndTinyCoordinates) {
    for (const float scale : {1e-30f, 1e-20f, 1e-13f, 1e-6f, 1e6f, 1e12f, 1e30f}) {
        const Triangle tri{kUnitTriangle.p0 * scale, kUnitTriangle.p1 * scale,
                           kUnitTriangle.p2 * scale};
        TriangleHit hit;
        ASSERT_TRUE(hit_triangle({{0.25f * scale, 0.25f * scale, scale}, {0, 0, -1}}, tri, hit))
            << scale;
        EXPECT_NEAR(hit.t / scale, 1.0f, 1e-6f) << scale;
    }
    // A far-away triangle: 1e6 units from the origin, 1 unit wide.
    const Triangle far{{1e6f, 0, 0}, {1e6f, 1, 0}, {1e6f, 0, 1}};
    TriangleHit hit;
    ASSERT_TRUE(hit_triangle({{0, 0.25f, 0.25f}, {1, 0, 0}}, far, hit));
    EXPECT_FLOAT_EQ(hit.t, 1e6f);
}

/// Double-precision reference (Moller-Trumbore); returns barycentrics to judge the margin.
bool reference_hit(const Ray& ray, const Triangle& tri, double& t, double& u, double& v) {
    const auto d = [](const glm::vec3& p) { return glm::dvec3(p); };
    const glm::dvec3 e1 = d(tri.p1) - d(tri.p0), e2 = d(tri.p2) - d(tri.p0);
    const glm::dvec3 p = glm::cross(d(ray.dir), e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return false;
    const glm::dvec3 s = d(ray.org) - d(tri.p0);
    u = glm::dot(s, p) / det;
    const glm::dvec3 q = glm::cross(s, e1);
    v = glm::dot(d(ray.dir), q) / det;
    t = glm::dot(e2, q) / det;
    return true;
}

/// The reference crossing's distance to the nearest edge (negative outside): each edge's
/// barycentric times twice the area over that edge's length.
double edge_margin(const Triangle& tri, double u, double v) {
    const glm::dvec3 p0(tri.p0), p1(tri.p1), p2(tri.p2);
    const double doubled_area = glm::length(glm::cross(p1 - p0, p2 - p0));
    return std::min({(1.0 - u - v) * doubled_area / glm::length(p2 - p1),
                     u * doubled_area / glm::length(p2 - p0),
                     v * doubled_area / glm::length(p1 - p0)});
}

/// What float can resolve around the triangle seen from `org`: 2^-18 of the largest coordinate
/// magnitude (the direction itself is rounded).
double float_resolution(const Triangle& tri, const glm::vec3& org) {
    return 0x1p-18 * std::max({glm::length(glm::dvec3(tri.p0)), glm::length(glm::dvec3(tri.p1)),
                               glm::length(glm::dvec3(tri.p2)), glm::length(glm::dvec3(org))});
}

TEST(TriangleIntersection, AgreesWithDoublePrecisionOnRandomRays) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
    const auto point = [&] { return glm::vec3(coord(rng), coord(rng), coord(rng)); };
    int decided = 0;
    for (int i = 0; i < 200000; ++i) {
        const Triangle tri{point(), point(), point()};
        const Ray ray{3.0f * point(), point()};
        double t, u, v;
        if (!reference_hit(ray, tri, t, u, v)) continue;
        const double margin = std::min({u, v, 1.0 - u - v});
        if (std::abs(margin) < 1e-4 || t < 1e-3) continue;  // too close to call in float
        ++decided;
        TriangleHit hit;
        const bool got = hit_triangle(ray, tri, hit);
        ASSERT_EQ(got, margin > 0.0) << "ray " << i;
        if (got) {
            EXPECT_NEAR(hit.t, t, 1e-4 * std::max(1.0, t)) << "ray " << i;
            EXPECT_NEAR(hit.u, u, 1e-3) << "ray " << i;
            EXPECT_NEAR(hit.v, v, 1e-3) << "ray " << i;
        }
    }
    EXPECT_GT(decided, 100000);
}

/// Needles (two corners close), slivers (the apex close to the opposite edge) and well-shaped
/// triangles, aspect ratios 1 to 1e5, at random orientations; rays from 1e-4 to 1 of the size
/// away towards points near the triangle. Where the crossing is farther from every edge than
/// float resolution (2^-18 of the coordinates; the direction itself is rounded), the hit/miss
/// matches a double-precision reference, and t is within 1e-5 of it, relative.
TEST(TriangleIntersection, NeedlesAndSliversFromCloseByAgreeWithDoublePrecision) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> normal;
    const auto random_unit = [&] {
        return glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
    };
    int decided = 0, hits = 0;
    for (int i = 0; i < 200000; ++i) {
        const double size = std::pow(10.0, 4.0 * unit(rng) - 2.0);
        const double aspect = std::pow(10.0, 5.0 * unit(rng));
        const glm::dvec3 centre = 10.0 * (glm::dvec3(unit(rng), unit(rng), unit(rng)) - 0.5);
        const glm::dvec3 a = random_unit(), b = glm::normalize(glm::cross(a, random_unit()));
        glm::dvec3 corners[3];
        if (i % 2) {  // needle: p1, p2 close together, far from p0
            corners[0] = centre - 0.5 * size * a;
            corners[1] = centre + 0.5 * size * a;
            corners[2] = corners[1] + size / aspect * b;
        } else {  // sliver: apex anywhere along the long edge, size / aspect above it
            corners[0] = centre - 0.5 * size * a;
            corners[1] = centre + 0.5 * size * a;
            corners[2] = centre + (unit(rng) - 0.5) * size * a + size / aspect * b;
        }
        const Triangle tri{glm::vec3(corners[0]), glm::vec3(corners[1]), glm::vec3(corners[2])};
        const double w0 = unit(rng), w1 = unit(rng) * (1.0 - w0);
        const glm::dvec3 target = glm::dvec3(tri.p0) * (1.0 - w0 - w1) + glm::dvec3(tri.p1) * w0 +
                                  glm::dvec3(tri.p2) * w1 +
                                  0.1 * size / aspect * (unit(rng) - 0.5) * b;  // near edges
        const double distance = size * std::pow(10.0, -4.0 * unit(rng));
        const glm::vec3 org(target - distance * random_unit());
        const Ray ray{org, glm::vec3(target) - org};
        double t, u, v;
        if (!reference_hit(ray, tri, t, u, v)) continue;
        const double margin = edge_margin(tri, u, v);
        if (std::abs(margin) < float_resolution(tri, org) || t <= 0.0) continue;
        ++decided;
        TriangleHit hit;
        const bool got = hit_triangle(ray, tri, hit);
        ASSERT_EQ(got, margin > 0.0) << "ray " << i << ", aspect " << aspect;
        if (got) {
            ++hits;
            ASSERT_NEAR(hit.t, t, 1e-5 * t) << "ray " << i << ", aspect " << aspect;
        }
    }
    EXPECT_GT(decided, 100000);
    EXPECT_GT(hits, 50000);
}

/// Small triangles far from the ray's origin (size 1e-5 to 1e-2 of the distance, as the
/// Conference's diffuse rays meet 40 per ray), rays aimed up to three sizes beside them: their
/// edge functions are often below their error bound, and those the ray's line passes well
/// beside are decided by separated_from_ray instead of the double-precision path. Every
/// decidable ray (crossing farther from each edge than float resolution) matches a
/// double-precision reference, and many were decided by the separation.
TEST(TriangleIntersection, FarSmallTrianglesBesideTheRayAgreeWithDoublePrecision) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> normal;
    const auto random_unit = [&] {
        return glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
    };
    int decided = 0, hits = 0, separated = 0;
    for (int i = 0; i < 200000; ++i) {
        const double distance = std::pow(10.0, 4.0 * unit(rng));
        const double size = distance * std::pow(10.0, 3.0 * unit(rng) - 5.0);
        const glm::dvec3 centre = 100.0 * (glm::dvec3(unit(rng), unit(rng), unit(rng)) - 0.5);
        const Triangle tri{glm::vec3(centre + size * random_unit()),
                           glm::vec3(centre + size * random_unit()),
                           glm::vec3(centre + size * random_unit())};
        const glm::dvec3 target = centre + 3.0 * size * unit(rng) * random_unit();
        const glm::vec3 org(target - distance * random_unit());
        const Ray ray{org, glm::vec3(target) - org};
        const WatertightRay wray = make_watertight_ray(ray);
        const ShearedTriangle<float> sheared = shear_triangle(wray, tri);
        separated += separated_from_ray(sheared, corner_errors(wray, sheared));
        double t, u, v;
        if (!reference_hit(ray, tri, t, u, v)) continue;
        const double margin = edge_margin(tri, u, v);
        if (std::abs(margin) < float_resolution(tri, org) || t <= 0.0) continue;
        ++decided;
        TriangleHit hit;
        const bool got = hit_triangle(ray, tri, hit);
        ASSERT_EQ(got, margin > 0.0) << "ray " << i << ", size " << size << " at " << distance;
        if (got) {
            ++hits;
            ASSERT_NEAR(hit.t, t, 1e-5 * t) << "ray " << i;
        }
    }
    EXPECT_GT(decided, 50000);
    EXPECT_GT(hits, 5000);
    EXPECT_GT(separated, 20000);
}

/// has_coincident_corners: such triangles are left out of the tracers' work, which is exact
/// only if the test never hits them, whichever corners coincide and however the ray meets the
/// segment they span (aimed at it, along it, from far away, at huge and tiny scales).
TEST(TriangleIntersection, TrianglesWithCoincidentCornersAreNeverHit) {
    std::mt19937 rng(19);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> normal;
    for (int i = 0; i < 200000; ++i) {
        const double scale = std::pow(10.0, 12.0 * unit(rng) - 6.0);
        const glm::vec3 a(scale * glm::dvec3(normal(rng), normal(rng), normal(rng)));
        const glm::vec3 b(scale * glm::dvec3(normal(rng), normal(rng), normal(rng)));
        const Triangle tri = i % 3 == 0   ? Triangle{a, a, b}
                             : i % 3 == 1 ? Triangle{a, b, b}
                                          : Triangle{b, a, b};
        ASSERT_TRUE(has_coincident_corners(tri));
        const glm::dvec3 on = glm::mix(glm::dvec3(a), glm::dvec3(b), unit(rng));
        const glm::dvec3 from = on + scale * std::pow(10.0, 6.0 * unit(rng) - 3.0) *
                                         glm::dvec3(normal(rng), normal(rng), normal(rng));
        const Ray ray{glm::vec3(from), glm::vec3(on - from)};
        TriangleHit hit;
        ASSERT_FALSE(hit_triangle(ray, tri, hit)) << "ray " << i;
    }
}

// --- Slab test -------------------------------------------------------------------------------

const Aabb kUnitBox{{0, 0, 0}, {1, 1, 1}};

bool hit_box(const Ray& ray, const Aabb& box, float& t_entry) {
    return intersect_box(make_slab_ray(ray), box, ray.tmax, t_entry);
}

TEST(BoxIntersection, HandComputed) {
    float t;
    ASSERT_TRUE(hit_box({{-1, 0.5f, 0.5f}, {1, 0, 0}}, kUnitBox, t));
    EXPECT_FLOAT_EQ(t, 1.0f);
    ASSERT_TRUE(hit_box({{0.5f, 0.5f, 0.5f}, {1, 0, 0}}, kUnitBox, t));  // origin inside
    EXPECT_FLOAT_EQ(t, 0.0f);
    EXPECT_FALSE(hit_box({{2, 0.5f, 0.5f}, {1, 0, 0}}, kUnitBox, t));            // behind
    EXPECT_FALSE(hit_box({{-1, 2.0f, 0.5f}, {1, 0, 0}}, kUnitBox, t));           // beside
    EXPECT_FALSE(hit_box({{-1, 0.5f, 0.5f}, {1, 0, 0}, 0, 0.5f}, kUnitBox, t));  // tmax short
}

TEST(BoxIntersection, AxisParallelRaysWithSignedZeros) {
    float t;
    for (const float zero : {0.0f, -0.0f}) {
        // Parallel to y and z, inside their slabs: hit.
        EXPECT_TRUE(hit_box({{-1, 0.5f, 0.5f}, {1, zero, zero}}, kUnitBox, t));
        EXPECT_TRUE(hit_box({{0.5f, 0.5f, 2}, {zero, zero, -1}}, kUnitBox, t));
        // Parallel and outside a slab: miss, whatever the sign of zero.
        EXPECT_FALSE(hit_box({{-1, 1.5f, 0.5f}, {1, zero, zero}}, kUnitBox, t));
        EXPECT_FALSE(hit_box({{-1, -0.5f, 0.5f}, {1, zero, zero}}, kUnitBox, t));
    }
}

TEST(BoxIntersection, OriginOnSlabPlaneNeverProducesNaN) {
    // (plane - org) * (1 / 0) is 0 * inf = NaN; such a grazing ray counts as a hit.
    float t = -1.0f;
    for (const float zero : {0.0f, -0.0f}) {
        ASSERT_TRUE(hit_box({{-1, 0.0f, 0.5f}, {1, zero, 0}}, kUnitBox, t));
        EXPECT_FLOAT_EQ(t, 1.0f);
        ASSERT_TRUE(hit_box({{-1, 1.0f, 1.0f}, {1, zero, zero}}, kUnitBox, t));
        EXPECT_FALSE(std::isnan(t));
    }
}

TEST(BoxIntersection, FlatBoxes) {
    const Aabb flat{{0, 0, 0.5f}, {1, 1, 0.5f}};  // a box of zero thickness, like one triangle
    float t;
    EXPECT_TRUE(hit_box({{0.5f, 0.5f, 2}, {0, 0, -1}}, flat, t));
    EXPECT_FLOAT_EQ(t, 1.5f);
    EXPECT_TRUE(hit_box({{0.5f, 0.5f, 2}, {0.01f, 0.01f, -1}}, flat, t));
}

TEST(BoxIntersection, ConservativeForRaysThatHitTriangles) {
    // Whenever a ray hits a triangle, it must hit the triangle's bounding box no later.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
    const auto point = [&] { return glm::vec3(coord(rng), coord(rng), coord(rng)); };
    int hits = 0;
    for (int i = 0; i < 200000; ++i) {
        const float scale = std::pow(10.0f, float(i % 13) - 6.0f);
        const Triangle tri{scale * point(), scale * point(), scale * point()};
        const Ray ray{3.0f * scale * point(), point()};
        TriangleHit hit;
        if (!hit_triangle(ray, tri, hit)) continue;
        ++hits;
        Aabb box;
        box.extend(tri.p0);
        box.extend(tri.p1);
        box.extend(tri.p2);
        float t_entry;
        ASSERT_TRUE(hit_box(ray, box, t_entry)) << "ray " << i;
        EXPECT_LE(t_entry, hit.t) << "ray " << i;
    }
    EXPECT_GT(hits, 1000);
}

}  // namespace
}  // namespace edacrt
