// The numerically hard cases, as properties over every method (naive, edacrt, dacrt, bvh,
// embree; closest and any hit) checked against a long-double reference:
// - closed meshes of long thin triangles (prisms of random orientation, side aspect ratios 10
//   to 1e6), rays from inside: every ray hits, t within 1e-5 relative;
// - one huge tilted triangle hit near its middle from close by;
// - rays spawned from random points of slivers (through the renderer's offset), random and
//   grazing directions: never their own triangle;
// - spheres scaled from 1e-30 to 1e30 and moved far from the origin, and a mix of huge and tiny
//   objects: every method agrees with the reference, or (Embree, outside the range its float
//   arithmetic covers) refuses the scene with an InputError.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <map>
#include <optional>
#include <random>

#include "geometry/offset.h"
#include "sanitizers.h"
#include "scene/builtin_scenes.h"
#include "scene/obj_loader.h"
#include "trace/ray_file.h"
#include "trace/tracer.h"
#include "util/error.h"

namespace edacrt {
namespace {

using ld = long double;
using ldvec3 = glm::vec<3, long double>;

ldvec3 to_ld(const glm::vec3& v) { return {ld(v.x), ld(v.y), ld(v.z)}; }

/// Möller-Trumbore in long double on the float inputs; a point within 1e-12 of an edge counts
/// as inside (the neighbour across the edge has the same t there).
std::optional<ld> intersect_ld(const Ray& ray, const Triangle& tri) {
    const ldvec3 p0 = to_ld(tri.p0), e1 = to_ld(tri.p1) - p0, e2 = to_ld(tri.p2) - p0;
    const ldvec3 dir = to_ld(ray.dir);
    const ldvec3 p = glm::cross(dir, e2);
    const ld det = glm::dot(e1, p);
    if (det == 0) return std::nullopt;
    const ldvec3 s = to_ld(ray.org) - p0;
    const ld u = glm::dot(s, p) / det;
    const ldvec3 q = glm::cross(s, e1);
    const ld v = glm::dot(dir, q) / det;
    constexpr ld kEdge = 1e-12L;
    if (u < -kEdge || v < -kEdge || u + v > 1 + kEdge) return std::nullopt;
    const ld t = glm::dot(e2, q) / det;
    if (!(t > 0 && t >= ld(ray.tmin) && t <= ld(ray.tmax))) return std::nullopt;
    if (t > ld(std::numeric_limits<float>::max())) return std::nullopt;  // not a float: a miss
    return t;
}

struct ReferenceHit {
    ld t = 0;
    std::int32_t prim = -1;
};

ReferenceHit closest_ld(const Scene& scene, const Ray& ray) {
    ReferenceHit best;
    for (std::size_t i = 0; i < scene.triangle_count(); ++i)
        if (const auto t = intersect_ld(ray, scene.corners(i)); t && (best.prim < 0 || *t < best.t))
            best = {*t, std::int32_t(i)};
    return best;
}

/// Every tracer configuration under test; Embree in each of its modes.
struct Candidate {
    std::string name;
    std::function<std::unique_ptr<Tracer>()> make;
};

std::vector<Candidate> all_methods() {
    std::vector<Candidate> out;
    for (const Method m : {Method::naive, Method::edacrt, Method::dacrt, Method::bvh})
        out.push_back({std::string(enum_name(kMethods, m)), [m] { return make_tracer(m); }});
#ifdef EDACRT_HAS_EMBREE
    for (const EmbreeMode mode : {EmbreeMode::single, EmbreeMode::packet8, EmbreeMode::stream})
        out.push_back({"embree " + std::string(enum_name(kEmbreeModes, mode)),
                       [mode] { return make_tracer(Method::embree, {}, mode); }});
#endif
    return out;
}

/// Traces `rays` with every method, closest and any hit, and hands each answer to `check`.
void trace_every_way(
    const Scene& scene, const std::vector<Ray>& rays,
    const std::function<void(const std::string&, Query, const std::vector<Hit>&)>& check) {
    for (const Candidate& method : all_methods()) {
        const auto tracer = method.make();
        tracer->set_scene(scene);
        std::vector<Hit> hits(rays.size());
        for (const Query query : {Query::closest, Query::any}) {
            tracer->trace(rays, hits, query);
            check(method.name, query, hits);
        }
    }
}

Scene make_scene(std::vector<glm::dvec3> positions,
                 std::vector<std::array<std::uint32_t, 3>> tris) {
    Scene scene;
    scene.source = "hard case";
    for (const glm::dvec3& p : positions) scene.positions.emplace_back(p);
    scene.triangles = std::move(tris);
    scene.triangle_materials.assign(scene.triangles.size(), 0);
    scene.materials.resize(1);
    return scene;
}

/// A uniformly random rotation (from a random unit quaternion).
glm::dmat3 random_rotation(std::mt19937& rng) {
    std::normal_distribution<double> normal;
    glm::dvec4 q(normal(rng), normal(rng), normal(rng), normal(rng));
    q /= glm::length(q);
    const double w = q.w, x = q.x, y = q.y, z = q.z;
    return glm::dmat3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y),
                      2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x),
                      2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
}

/// A closed prism along its local z: a regular `sides`-gon of circumradius 1 swept over a length
/// `aspect` times its side, so each side face is two triangles of that aspect ratio; caps are
/// fans. Rotated by `rotation`, centred at `centre`.
struct Prism {
    Scene scene;
    glm::dmat3 rotation;
    glm::dvec3 centre;
    double inradius, length;
};

Prism thin_prism(int sides, double aspect, const glm::dmat3& rotation, glm::dvec3 centre) {
    const double side = 2.0 * std::sin(M_PI / sides);
    const double length = aspect * side;
    std::vector<glm::dvec3> positions;
    for (const double z : {-0.5 * length, 0.5 * length})
        for (int k = 0; k < sides; ++k) {
            const double a = 2.0 * M_PI * k / sides;
            positions.push_back(centre + rotation * glm::dvec3(std::cos(a), std::sin(a), z));
        }
    std::vector<std::array<std::uint32_t, 3>> tris;
    const auto n = std::uint32_t(sides);
    for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t k1 = (k + 1) % n;
        tris.push_back({k, k1, n + k1});
        tris.push_back({k, n + k1, n + k});
    }
    for (std::uint32_t k = 1; k + 1 < n; ++k) {
        tris.push_back({0, k + 1, k});
        tris.push_back({n, n + k, n + k + 1});
    }
    return {make_scene(positions, tris), rotation, centre, std::cos(M_PI / sides), length};
}

/// A unit direction within `angle` radians of `axis` (both signs of the axis).
glm::dvec3 near_axis(const glm::dvec3& axis, double angle, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const glm::dvec3 helper = std::abs(axis.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 b1 = glm::normalize(glm::cross(axis, helper)), b2 = glm::cross(axis, b1);
    const double phi = 2.0 * M_PI * unit(rng);
    const glm::dvec3 d =
        std::cos(angle) * axis + std::sin(angle) * (std::cos(phi) * b1 + std::sin(phi) * b2);
    return unit(rng) < 0.5 ? d : -d;
}

glm::dvec3 random_direction(std::mt19937& rng) {
    std::normal_distribution<double> normal;
    glm::dvec3 d(normal(rng), normal(rng), normal(rng));
    return glm::normalize(d);
}

/// Traces `rays` with every method, closest and any hit, and checks each against the
/// long-double reference: every ray hits (when `all_hit`), the hit/miss of closest hits matches
/// the reference, and t is within `tolerance` relative. Returns the rays checked per method.
/// Embree decides for itself which triangles a ray passes through: `embree_allowance` wrong
/// answers are tolerated from it (and counted in embree_wrong), none from our methods. Embree
/// may refuse a scene or rays with an InputError (counted in embree_refused).
std::size_t embree_wrong = 0, embree_refused = 0;

/// Per method: rays checked against the reference (closest and any hit counted apart) and wrong
/// answers, printed when the suite ends.
struct Tally {
    std::size_t checked = 0, wrong = 0;
};
std::map<std::string, Tally>& tallies() {
    static std::map<std::string, Tally> t;
    return t;
}

class PrintTallies : public ::testing::Environment {
    void TearDown() override {
        for (const auto& [name, tally] : tallies())
            std::printf("hard cases, %-15s %7zu queries checked, %4zu wrong\n", name.c_str(),
                        tally.checked, tally.wrong);
    }
};
const auto* const kPrintTallies = ::testing::AddGlobalTestEnvironment(new PrintTallies);

/// A distance in full (std::to_string prints 1e-35 as 0.000000).
std::string decimal(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", t);
    return text;
}

std::size_t expect_reference_hits(const Scene& scene, const std::vector<Ray>& rays,
                                  const std::string& label, bool all_hit, double tolerance = 1e-5,
                                  std::size_t embree_allowance = 0) {
    std::vector<ReferenceHit> reference;
    for (const Ray& ray : rays) reference.push_back(closest_ld(scene, ray));
    for (std::size_t i = 0; all_hit && i < rays.size(); ++i) {
        EXPECT_GE(reference[i].prim, 0) << label << ": the reference misses ray " << i;
    }
    for (const Candidate& method : all_methods()) {
        const bool embree = method.name.starts_with("embree");
        const auto tracer = method.make();
        std::vector<Hit> hits(rays.size());
        if (embree) {
            try {
                tracer->set_scene(scene);
                tracer->trace(rays, hits, Query::closest);
            } catch (const InputError& e) {
                EXPECT_TRUE(std::string(e.what()).starts_with("Embree cannot trace")) << e.what();
                ++embree_refused;
                continue;
            }
        }
        tracer->set_scene(scene);
        const std::size_t allowed = embree ? embree_allowance : 0;
        std::size_t wrong = 0;
        tracer->trace(rays, hits, Query::closest);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const bool ok = hits[i].hit() == (reference[i].prim >= 0) &&
                            (!hits[i].hit() || (std::isfinite(hits[i].t) &&
                                                std::abs(ld(hits[i].t) - reference[i].t) <=
                                                    ld(tolerance) * reference[i].t));
            // The barycentrics of a reported hit lie in the triangle, to rounding.
            const bool inside = !hits[i].hit() || (hits[i].u >= 0.0f && hits[i].v >= 0.0f &&
                                                   hits[i].u + hits[i].v <= 1.0f + 1e-6f);
            EXPECT_TRUE(inside) << label << ", " << method.name << ", ray " << i << ": u "
                                << hits[i].u << ", v " << hits[i].v;
            if (!ok && wrong++ < 3 && !allowed)
                ADD_FAILURE() << label << ", " << method.name << ", closest, ray " << i << ": got "
                              << (hits[i].hit() ? "t " + decimal(hits[i].t) : "a miss")
                              << ", reference "
                              << (reference[i].prim >= 0 ? "t " + decimal(double(reference[i].t))
                                                         : "a miss");
        }
        EXPECT_LE(wrong, allowed) << label << ", " << method.name << ", closest: wrong hits";
        if (embree) embree_wrong += wrong;
        tallies()[method.name].checked += rays.size();
        tallies()[method.name].wrong += wrong;
        wrong = 0;
        tracer->trace(rays, hits, Query::any);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const bool ok = hits[i].hit() == (reference[i].prim >= 0) &&
                            (!hits[i].hit() || (std::isfinite(hits[i].t) && hits[i].t > 0.0f &&
                                                hits[i].t <= rays[i].tmax));
            if (!ok && wrong++ < 3 && !allowed)
                ADD_FAILURE() << label << ", " << method.name << ", any hit, ray " << i;
        }
        EXPECT_LE(wrong, allowed) << label << ", " << method.name << ", any hit: wrong answers";
        if (embree) embree_wrong += wrong;
        tallies()[method.name].checked += rays.size();
        tallies()[method.name].wrong += wrong;
    }
    return rays.size();
}

TEST(HardCases, ThinPrismsFromInsideNeverLeak) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::size_t checked = 0;
    Scene all;  // every prism in one scene, for a batch large enough to recurse and sample
    all.source = "all prisms";
    all.materials.resize(1);
    std::vector<Ray> all_rays;
    for (const int sides : {3, 4, 7, 32})
        for (const double aspect : {10.0, 1e2, 1e3, 1e4, 1e5, 1e6})
            for (int orientation = 0; orientation < 2; ++orientation) {
                const glm::dvec3 centre =
                    10.0 * (glm::dvec3(unit(rng), unit(rng), unit(rng)) - 0.5);
                const Prism prism = thin_prism(sides, aspect, random_rotation(rng), centre);
                const glm::dvec3 axis = prism.rotation * glm::dvec3(0, 0, 1);
                std::vector<Ray> rays;
                for (int i = 0; i < 120; ++i) {
                    // Well inside: a quarter of the inradius from the axis (float rounding of
                    // the corners moves them by up to 2^-24 of the length).
                    const double r = 0.25 * prism.inradius * std::sqrt(unit(rng));
                    const double phi = 2.0 * M_PI * unit(rng);
                    const double z = (unit(rng) - 0.5) * 0.8 * prism.length;
                    const glm::dvec3 org =
                        prism.centre +
                        prism.rotation * glm::dvec3(r * std::cos(phi), r * std::sin(phi), z);
                    glm::dvec3 dir;
                    switch (i % 4) {
                        case 0:
                            dir = random_direction(rng);
                            break;
                        case 1:
                            dir = near_axis(axis, std::pow(10.0, -6.0 * unit(rng)), rng);
                            break;
                        case 2:
                            dir = near_axis(axis, M_PI / 2, rng);
                            break;  // across
                        default:
                            dir = axis * (i % 8 < 4 ? 1.0 : -1.0);
                            break;
                    }
                    rays.push_back({glm::vec3(org), glm::vec3(dir)});
                }
                // Embree's own inside test leaks rays nearly parallel to triangles of 1:1e4
                // and thinner (measured: up to 7 of 120 rays per prism; at 1:1e4, one ray of
                // the prisms a Clang build generates); ours must not.
                checked += expect_reference_hits(
                    prism.scene, rays,
                    std::to_string(sides) + "-sided prism, aspect " + std::to_string(aspect), true,
                    1e-5, aspect >= 1e4 ? rays.size() / 8 : 0);
                if (HasFailure()) return;
                const auto base = std::uint32_t(all.positions.size());
                all.positions.insert(all.positions.end(), prism.scene.positions.begin(),
                                     prism.scene.positions.end());
                for (const auto& tri : prism.scene.triangles)
                    all.triangles.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
                all_rays.insert(all_rays.end(), rays.begin(), rays.end());
            }
    EXPECT_EQ(checked, 4u * 6 * 2 * 120);
    all.triangle_materials.assign(all.triangles.size(), 0);
    expect_reference_hits(all, all_rays, "all prisms in one scene", true, 1e-5,
                          all_rays.size() / 8);
    std::printf("Embree: %zu wrong answers among the prisms' rays (allowed from aspect 1e4)\n",
                embree_wrong);
}

TEST(HardCases, HugeTiltedTriangleHitNearItsMiddle) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const double size : {1e3, 1e5, 1e7, 1e8, 1e9}) {
        const glm::dmat3 rotation = random_rotation(rng);
        const Scene scene = make_scene({rotation * glm::dvec3(-size, -size, 0.3 * size),
                                        rotation * glm::dvec3(size, -0.5 * size, -0.2 * size),
                                        rotation * glm::dvec3(0.1 * size, size, 0.1 * size)},
                                       {{0, 1, 2}});
        const glm::dvec3 n = glm::dvec3(unit_normal(scene.corners(0)));
        const glm::dvec3 middle = (glm::dvec3(scene.positions[0]) + glm::dvec3(scene.positions[1]) +
                                   glm::dvec3(scene.positions[2])) /
                                  3.0;
        std::vector<Ray> rays;
        for (int i = 0; i < 200; ++i) {
            // From 1e-5 of its size (far above the float spacing of the origin) to its size.
            const double distance = size * std::pow(10.0, -5.0 * unit(rng));
            const glm::dvec3 target =
                middle + 0.1 * size * (glm::dvec3(unit(rng), unit(rng), unit(rng)) - 0.5);
            const glm::dvec3 on_plane = target - glm::dot(target - middle, n) * n;
            const glm::dvec3 dir = glm::normalize(n + 0.5 * random_direction(rng));
            const double side = i % 2 ? 1.0 : -1.0;
            rays.push_back({glm::vec3(on_plane - side * distance * dir), glm::vec3(side * dir)});
        }
        expect_reference_hits(scene, rays, "triangle of size " + std::to_string(size), true);
    }
}

/// `count` slivers (aspect ratios 10 to 1e6) of random orientation, scattered in a box.
Scene sliver_soup(int count, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::dvec3> positions;
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (int i = 0; i < count; ++i) {
        const double aspect = std::pow(10.0, 1.0 + 5.0 * unit(rng));
        const double length = std::pow(10.0, 2.0 * unit(rng));
        const glm::dmat3 rotation = random_rotation(rng);
        const glm::dvec3 centre = 100.0 * glm::dvec3(unit(rng), unit(rng), unit(rng));
        const double apex = unit(rng);  // needle (apex at an end) or sliver (apex in between)
        const auto base = std::uint32_t(positions.size());
        positions.push_back(centre + rotation * glm::dvec3(-0.5 * length, 0, 0));
        positions.push_back(centre + rotation * glm::dvec3(0.5 * length, 0, 0));
        positions.push_back(centre +
                            rotation * glm::dvec3((apex - 0.5) * length, length / aspect, 0));
        tris.push_back({base, base + 1, base + 2});
    }
    return make_scene(positions, tris);
}

TEST(HardCases, RaysSpawnedFromSliversNeverHitTheirOwnTriangle) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const Scene scene = sliver_soup(300, rng);
    std::vector<Ray> rays;
    std::vector<std::int32_t> own;
    for (int i = 0; i < 6000; ++i) {
        const auto prim = std::int32_t(rng() % scene.triangle_count());
        const Triangle tri = scene.corners(std::size_t(prim));
        const float a = unit(rng), b = unit(rng) * (1.0f - a);
        const SurfacePoint point = surface_point(tri, a, b);
        const glm::vec3 n = unit_normal(tri);
        glm::vec3 dir;
        if (i % 2) {
            dir = glm::vec3(random_direction(rng));
        } else {  // grazing: 1e-1 to 1e-6 rad above the plane, on either side
            const double angle = std::pow(10.0, -1.0 - 5.0 * double(unit(rng)));
            const glm::dvec3 in_plane =
                glm::normalize(glm::cross(glm::dvec3(n), random_direction(rng)));
            const double side = i % 4 ? 1.0 : -1.0;
            dir = glm::vec3(std::cos(angle) * in_plane + side * std::sin(angle) * glm::dvec3(n));
        }
        rays.push_back({offset_ray_origin(point, n, dir), dir, kSpawnTmin});
        own.push_back(prim);
    }
    trace_every_way(scene, rays, [&](const std::string& method, Query query, const auto& hits) {
        std::size_t self_hits = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) self_hits += hits[i].prim == own[i];
        EXPECT_EQ(self_hits, 0u) << method << (query == Query::any ? ", any" : "");
        tallies()[method].checked += rays.size();
        tallies()[method].wrong += self_hits;
    });
}

/// Rays that must hit a closed sphere of radius `radius` at `centre`: from inside, and from
/// outside towards points well inside it.
std::vector<Ray> sphere_rays(glm::dvec3 centre, double radius, std::mt19937& rng, int count) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 inside = centre + 0.5 * radius * random_direction(rng) * unit(rng);
        if (i % 2) {
            rays.push_back({glm::vec3(inside), glm::vec3(random_direction(rng))});
        } else {
            const glm::dvec3 outside = centre + 3.0 * radius * random_direction(rng);
            rays.push_back({glm::vec3(outside), glm::vec3(glm::normalize(inside - outside))});
        }
    }
    return rays;
}

Scene transformed(const Scene& base, double scale, glm::dvec3 offset) {
    Scene scene = base;
    for (glm::vec3& p : scene.positions) p = glm::vec3(glm::dvec3(p) * scale + offset);
    return scene;
}

TEST(HardCases, SpheresAtEveryScaleAndFarFromTheOrigin) {
    const Scene unit_sphere = make_builtin_scene("builtin:sphere:subdiv=2");
    std::mt19937 rng(9);
    for (const double scale : {1e-30, 1e-20, 1e-12, 1e-6, 1.0, 1e6, 1e12, 1e20, 1e30})
        for (const double far : {0.0, 1e3, 1e6}) {
            const glm::dvec3 offset = far * scale * glm::dvec3(1.0, -0.7, 0.4);
            const Scene scene = transformed(unit_sphere, scale, offset);
            const std::vector<Ray> rays = sphere_rays(offset, scale, rng, 200);
            const std::string label = "sphere of radius " + std::to_string(scale) + " at " +
                                      std::to_string(far) + " radii";
            embree_refused = 0;
            expect_reference_hits(scene, rays, label, true);
#ifdef EDACRT_HAS_EMBREE
            // Embree covers sizes above 1e-18 and coordinates below 1e12 (embree_tracer.cpp):
            // it must work well inside that range and refuse (not answer wrong) outside it.
            const double largest = 3.0 * scale * (1.0 + far);
            if (scale >= 1e-12 && largest <= 1e9) {
                EXPECT_EQ(embree_refused, 0u) << label;
            }
            if (scale <= 1e-20 || largest >= 1e13) {
                EXPECT_EQ(embree_refused, 3u) << label;
            }
#endif
            if (HasFailure()) return;
        }
}

TEST(HardCases, FarRaysThatMissNeverHit) {
    // Rays from 1e3 to 1e7 units away at a unit sphere: half pass 0.01 to 60 units beside it
    // (found by the adversarial campaign: naive reported hits 1000 triangle sizes outside the
    // triangle for these), half aim inside it. The float test resolves a ray to the rounding
    // of its origin's coordinates (the sheared corners are differences from the origin):
    // 2^-24 of 1e6 is 0.06, and a few such roundings add up. Rays that pass within 5e-7 of
    // their distance of the sphere's outline are left out.
    const Scene sphere = make_builtin_scene("builtin:sphere:subdiv=3");
    std::mt19937 rng(33);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const double distance : {1e3, 1e4, 1e5, 1e6, 1e7}) {
        const double margin = 5e-7 * distance + 0.01;
        std::vector<Ray> rays;
        for (int i = 0; i < 1000; ++i) {
            const glm::dvec3 from = distance * random_direction(rng);
            const glm::dvec3 axis = glm::normalize(-from);
            const glm::dvec3 side = glm::normalize(glm::cross(axis, random_direction(rng)));
            const bool miss = i % 2 || margin > 0.9;
            // A subdivided sphere's faces lie within 0.01 inside the sphere.
            const double off =
                miss ? 1.0 + margin * std::pow(6000.0, unit(rng)) : (0.98 - margin) * unit(rng);
            const glm::dvec3 to = off * side;
            rays.push_back({glm::vec3(from), glm::vec3(glm::normalize(to - from))});
        }
        expect_reference_hits(sphere, rays, "rays from " + std::to_string(distance), false);
    }
}

/// A convex polygon of `corners` corners on the unit circle in the plane z = 0, triangulated
/// as the OBJ loader triangulates a face: a fan from corner 0, of thin triangles.
Scene polygon_fan(std::uint32_t corners) {
    std::vector<glm::dvec3> positions;
    for (std::uint32_t k = 0; k < corners; ++k) {
        const double a = 2.0 * M_PI * k / corners;
        positions.push_back({std::cos(a), std::sin(a), 0.0});
    }
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (std::uint32_t k = 1; k + 1 < corners; ++k) tris.push_back({0, k, k + 1});
    return make_scene(positions, tris);
}

TEST(HardCases, FansOfAMillionThinTrianglesNeitherOverflowTheStackNorLeak) {
    // Every ray enters every child box near the shared corner, so every split candidate costs
    // the same: the recursion once went a level deeper per few triangles and overflowed the
    // stack from 60k corners. Rays fall on the plane from above, at the shared corner (where
    // the barycentrics of the thin triangles came out at -1.5e-3), across the polygon and
    // outside it; the polygon's edge is 1e-11 from the circle, so points off the circle by
    // 1e-3 have a clear answer. Under the sanitizers (20 times slower, and larger frames, so
    // an unbounded recursion overflows sooner) 200k corners, still beyond the 60k that
    // overflowed: the million took 330 s there.
    for (const std::uint32_t corners : {1000u, test::kSanitized ? 200000u : 1000000u}) {
        const Scene scene = polygon_fan(corners);
        std::mt19937 rng(corners);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::vector<Ray> rays;
        std::vector<bool> inside;
        while (rays.size() < 300) {
            glm::dvec2 p(2.4 * unit(rng) - 1.2, 2.4 * unit(rng) - 1.2);
            if (rays.size() % 3 == 0)  // about the shared corner (1, 0), within 1e-6 to 1e-2
                p = glm::dvec2(1.0, 0.0) + std::pow(10.0, -6.0 + 4.0 * unit(rng)) *
                                               glm::dvec2(-unit(rng), 2.0 * unit(rng) - 1.0);
            const double r = glm::length(p);
            if (std::abs(r - 1.0) < 1e-3 && rays.size() % 3 != 0) continue;
            const glm::dvec3 from(p.x + 0.3 * unit(rng), p.y - 0.2 * unit(rng), 1.0);
            rays.push_back({glm::vec3(from), glm::vec3(glm::normalize(glm::dvec3(p, 0.0) - from))});
            inside.push_back(r < 1.0);
        }
        trace_every_way(scene, rays, [&](const std::string& method, Query query, const auto& hits) {
            std::size_t wrong = 0;
            for (std::size_t i = 0; i < rays.size(); ++i) {
                // Near the shared corner the polygon is as wide as a float's rounding: the
                // answer there is checked only through its barycentrics.
                const bool decided = i % 3 != 0;
                if (decided && hits[i].hit() != bool(inside[i])) ++wrong;
                if (hits[i].hit() && query == Query::closest) {
                    EXPECT_TRUE(hits[i].u >= 0.0f && hits[i].v >= 0.0f &&
                                hits[i].u + hits[i].v <= 1.0f + 1e-6f)
                        << method << ", ray " << i << ": u " << hits[i].u << ", v " << hits[i].v;
                    const double t = double(rays[i].org.z) / -double(rays[i].dir.z);
                    EXPECT_NEAR(hits[i].t, t, 1e-5 * t) << method << ", ray " << i;
                }
            }
            EXPECT_EQ(wrong, 0u) << method << (query == Query::any ? ", any" : "") << ", "
                                 << corners << " corners";
            tallies()[method].checked += rays.size();
            tallies()[method].wrong += wrong;
        });
    }
}

/// Spheres of radius 1e-3 to 10 at up to 100 units, rays from outside towards them and from
/// inside, with directions of each length: a distance d is then a t of d / length.
void expect_hits_with_direction_lengths(std::initializer_list<double> lengths, unsigned seed) {
    const Scene unit_sphere = make_builtin_scene("builtin:sphere:subdiv=2");
    std::mt19937 rng(seed);
    for (const double length : lengths)
        for (const double radius : {1e-3, 1.0, 10.0}) {
            const glm::dvec3 centre = 10.0 * radius * random_direction(rng);
            const Scene scene = transformed(unit_sphere, radius, centre);
            std::vector<Ray> rays = sphere_rays(centre, radius, rng, 200);
            for (Ray& ray : rays) {
                ray.dir = glm::vec3(glm::dvec3(ray.dir) * length);
                ASSERT_EQ(validate_ray(ray), "");
            }
            char label[64];
            std::snprintf(label, sizeof label, "length %g, radius %g", length, radius);
            expect_reference_hits(scene, rays, label, false);
        }
}

TEST(HardCases, ShortDirectionsGiveTheSameHitsAsUnitOnes) {
    // From the shortest valid (validate_ray: 2^-64) to 1e-10 long: t up to 1e21. (Below 1e-37,
    // where the other components turn denormal, the box tests disagreed: such rays are
    // refused.)
    expect_hits_with_direction_lengths({0x1p-64 * std::sqrt(3.0), 1e-19, 1e-15, 1e-10}, 77);
}

TEST(HardCases, LongDirectionsGiveTheSameHitsAsUnitOnes) {
    // 1e10 to 1e33 long: t near 1e-35, and the sheared z of the corners as small, so the
    // products of t's numerator (edge function times z) went denormal and float t lost up to a
    // third of its value (found by the fan fuzzer: a direction of 1.2e33 against a fan of thin
    // triangles). Such products are now refined in double (kSmallestDistanceProduct).
    expect_hits_with_direction_lengths({1e10, 1e20, 1e30, 1e33}, 33);
}

TEST(HardCases, OriginsTwoToTheFiftyThreeAwayGetNoFalseHits) {
    // Found by the trace fuzzer: from 2^53 away the corners' differences from the origin are
    // exact in double but the double shear (6.75 + 1.5e16) is not, and naive hit a unit
    // triangle where the line passes 1.5e16 beside it. The line along (-1, -1, -1) from
    // (x, y, z) meets the plane x = 0 at (y - x, z - x): far outside the triangle.
    const Scene scene = make_scene({{0, 0, -2}, {0, 2, -2}, {0, 1, -1}}, {{0, 1, 2}});
    std::mt19937 rng(53);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Ray> rays = {{{0x1.b4b5fep+53f, -4.75f, -4.75f}, {-1, -1, -1}}};
    while (rays.size() < 4000) {
        const double x = std::ldexp(1.0 + unit(rng), 50 + int(rng() % 8));
        rays.push_back({glm::vec3(float(x), float(16 * unit(rng) - 8), float(16 * unit(rng) - 8)),
                        {-1, -1, -1}});
    }
    expect_reference_hits(scene, rays, "origins 2^50 to 2^58 away", false);
}

TEST(HardCases, HugeAndTinyObjectsInOneScene) {
    // A 1e-3 sphere beside a 1e4 one, 1e5 apart, then the mix moved 1e3 from the origin (the
    // float spacing there, 6e-5, still resolves the small sphere).
    const Scene sphere = make_builtin_scene("builtin:sphere:subdiv=3");
    std::mt19937 rng(21);
    for (const double far : {0.0, 1e3}) {
        const glm::dvec3 small_centre(far, 0.0, 0.0), large_centre(far + 1e5, 0.0, 0.0);
        Scene scene = transformed(sphere, 1e-3, small_centre);
        const Scene large = transformed(sphere, 1e4, large_centre);
        const auto base = std::uint32_t(scene.positions.size());
        scene.positions.insert(scene.positions.end(), large.positions.begin(),
                               large.positions.end());
        for (auto tri : large.triangles)
            scene.triangles.push_back({tri[0] + base, tri[1] + base, tri[2] + base});
        scene.triangle_materials.assign(scene.triangles.size(), 0);
        std::vector<Ray> rays = sphere_rays(small_centre, 1e-3, rng, 300);
        const std::vector<Ray> large_rays = sphere_rays(large_centre, 1e4, rng, 300);
        rays.insert(rays.end(), large_rays.begin(), large_rays.end());
        embree_refused = 0;
        expect_reference_hits(scene, rays, "mix at " + std::to_string(far), true);
        EXPECT_EQ(embree_refused, 0u);
    }
}

}  // namespace
}  // namespace edacrt

namespace edacrt {
namespace {

TEST(HardCases, TrianglesAreNumberedInFileOrderDegenerateOnesIncluded) {
    // A row of unit triangles along x, with degenerate faces (repeated index, coincident corners,
    // collinear) and a quad (two fan triangles) mixed in: the hit `prim` is the triangle's number
    // in file order after triangulation, for every method.
    std::string obj = "v 0 0 0\n";  // 1: the point every degenerate face reuses
    std::vector<int> proper;        // numbers of the triangles that can be hit
    int vertex = 2, triangle = 0;
    for (int k = 0; k < 12; ++k) {
        const float x = 2.0f * float(k);
        obj += "v " + std::to_string(x) + " 0 0\nv " + std::to_string(x + 1) + " 0 0\nv " +
               std::to_string(x) + " 1 0\nv " + std::to_string(x + 1) + " 1 0\n";
        const std::string a = std::to_string(vertex), b = std::to_string(vertex + 1),
                          c = std::to_string(vertex + 2);
        vertex += 4;
        switch (k % 4) {
            case 0:
                obj += "f 1 1 " + a + "\n";
                break;  // repeated index
            case 1:
                obj += "f " + a + " " + a + " " + b + "\n";
                break;  // coincident
            case 2:
                obj += "f " + a + " " + b + " 1\n";
                break;  // collinear (y = 0)
            default:    // a quad beside the row (y from 2 to 3)
                obj += "v " + std::to_string(x) + " 2 0\nv " + std::to_string(x + 1) + " 2 0\nv " +
                       std::to_string(x + 1) + " 3 0\nv " + std::to_string(x) + " 3 0\n";
                obj += "f " + std::to_string(vertex) + " " + std::to_string(vertex + 1) + " " +
                       std::to_string(vertex + 2) + " " + std::to_string(vertex + 3) + "\n";
                vertex += 4;
                break;
        }
        triangle += k % 4 == 3 ? 2 : 1;  // the degenerate face (or the quad's two triangles)
        obj += "f " + a + " " + b + " " + c + "\n";
        proper.push_back(triangle++);
    }
    const Scene scene = parse_obj(
        obj, "row.obj", [](const std::string&) -> std::string { throw InputError("no MTL"); });
    ASSERT_EQ(scene.triangle_count(), std::size_t(triangle));
    std::vector<Ray> rays;
    std::vector<std::int32_t> expected;
    for (const int prim : proper) {
        const Triangle tri = scene.corners(std::size_t(prim));
        const glm::vec3 centroid = (tri.p0 + tri.p1 + tri.p2) / 3.0f;
        rays.push_back({centroid + glm::vec3(0, 0, 1), {0, 0, -1}});
        expected.push_back(prim);
    }
    trace_every_way(scene, rays, [&](const std::string& method, Query, const auto& hits) {
        for (std::size_t i = 0; i < rays.size(); ++i)
            EXPECT_EQ(hits[i].prim, expected[i]) << method << ", ray " << i;
    });
}

}  // namespace
}  // namespace edacrt

namespace edacrt {
namespace {

TEST(HardCases, HitsBeyondTheFloatRangeAreMissesNeverInfiniteDistances) {
    // A triangle at z = 0 and one at z = 3e38 (beside it, at x = 10); rays along +z. A hit at
    // t = 1e38 or 3e38 is a float; one at 6e38 is not, and cannot be reported as t = inf.
    Scene scene;
    scene.source = "far planes";
    for (const float z : {0.0f, 3e38f}) {
        const auto base = std::uint32_t(scene.positions.size());
        const float x = z == 0.0f ? 0.0f : 10.0f;
        scene.positions.insert(scene.positions.end(),
                               {{x - 1, -1, z}, {x + 2, -1, z}, {x - 1, 2, z}});
        scene.triangles.push_back({base, base + 1, base + 2});
    }
    scene.triangle_materials.assign(2, 0);
    scene.materials.resize(1);
    const std::vector<Ray> rays = {{{0, 0, -1e38f}, {0, 0, 1}},    // t = 1e38
                                   {{0, 0, -3e38f}, {0, 0, 1}},    // t = 3e38
                                   {{10, 0, 1.0f}, {0, 0, 1}},     // t = 3e38 (the far one)
                                   {{10, 0, -3e38f}, {0, 0, 1}},   // t = 6e38: beyond floats
                                   {{0, 0, -3e38f}, {0, 0, -1}}};  // nothing there
    const bool expected_hit[] = {true, true, true, false, false};
    const float expected_t[] = {1e38f, 3e38f, 3e38f, 0, 0};
    for (const Candidate& method : all_methods()) {
        const auto tracer = method.make();
        std::vector<Hit> hits(rays.size());
        try {
            tracer->set_scene(scene);
            tracer->trace(rays, hits, Query::closest);
        } catch (const InputError& e) {
            // Embree refuses coordinates beyond 1e12 rather than answering wrong.
            EXPECT_TRUE(method.name.starts_with("embree")) << method.name << ": " << e.what();
            continue;
        }
        for (std::size_t i = 0; i < rays.size(); ++i) {
            EXPECT_EQ(hits[i].hit(), expected_hit[i]) << method.name << ", ray " << i;
            if (hits[i].hit()) {
                EXPECT_TRUE(std::isfinite(hits[i].t)) << method.name << ", ray " << i;
                EXPECT_NEAR(hits[i].t, expected_t[i], 1e-6 * expected_t[i]) << method.name;
            }
        }
        tracer->trace(rays, hits, Query::any);
        for (std::size_t i = 0; i < rays.size(); ++i)
            EXPECT_EQ(hits[i].hit(), expected_hit[i]) << method.name << ", any hit, ray " << i;
    }
}

}  // namespace
}  // namespace edacrt
